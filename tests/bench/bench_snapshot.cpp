// Off-screen snapshot cost (OSMesa, llvmpipe on the CPU). Target: a 1920x1080 snapshot of a
// 100,000-triangle mesh in under 0.5 s on the 2-core reference machine. Never run by ctest.
//
//   bench_snapshot [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <memory>

#include "sutura/render/renderer.hpp"
#include "test_meshes.hpp"

namespace sutura::render {
namespace {

using testing::TestMesh;

// A tube of 2 * rings * 100 triangles with a scalar (distance along it) per vertex.
struct TubeScene {
  TestMesh mesh;
  std::vector<float> scalars;
  Scene scene;

  TubeScene(int triangles, bool with_scalars)
      : mesh(testing::tube(1.0f, 12.0f, triangles / 200, 100)) {
    scene.surfaces.push_back(mesh.surface());
    if (with_scalars) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
        scalars.push_back(mesh.positions[3 * v]);
      scene.surfaces[0].scalars = scalars;
      scene.color_map = ColorMap{ColorMapName::Viridis, -6.0f, 6.0f, "x [mm]", true};
    }
    PolylineItem incision;
    for (int i = 0; i <= 40; ++i)
      incision.points.push_back({-4.0f + 0.2f * static_cast<float>(i), 0.0f, -1.0f});
    scene.polylines.push_back(incision);
    scene.points.push_back({{{-4.0f, 0.0f, -1.0f}, {4.0f, 0.0f, -1.0f}}});
  }
};

struct Gl {
  std::unique_ptr<GlContext> context = create_offscreen_context();
  Renderer renderer{*context};
};

Gl& gl() {
  static Gl instance;
  return instance;
}

// Args: triangles, MSAA samples, scalars + legend (0/1), wireframe (0/1).
void BM_Snapshot(benchmark::State& state) {
  TubeScene tube(static_cast<int>(state.range(0)), state.range(2) != 0);
  tube.scene.surfaces[0].wireframe = state.range(3) != 0;
  RenderOptions options;
  options.samples = static_cast<int>(state.range(1));
  const Camera camera = fit_camera(scene_bounds(tube.scene), 1920.0f / 1080.0f);
  for (auto _ : state) {
    Image image = gl().renderer.render(tube.scene, camera, 1920, 1080, options);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["triangles"] = static_cast<double>(tube.mesh.triangles.size() / 3);
}
BENCHMARK(BM_Snapshot)
    ->ArgNames({"tris", "samples", "scalars", "wire"})
    ->Args({100000, 4, 0, 0})
    ->Args({100000, 1, 0, 0})
    ->Args({100000, 4, 1, 0})
    ->Args({100000, 4, 0, 1})
    ->Args({20000, 4, 0, 0})
    ->Args({0, 4, 0, 0})  // fixed cost: clear, resolve, read back (a polyline and 2 points)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// What `sutura replay` pays for one picture: context, shaders, render and PNG encoding.
void BM_ColdSnapshotToPng(benchmark::State& state) {
  TubeScene tube(100000, true);
  const Camera camera = fit_camera(scene_bounds(tube.scene), 1920.0f / 1080.0f);
  for (auto _ : state) {
    auto context = create_offscreen_context();
    Renderer renderer(*context);
    const Image image = renderer.render(tube.scene, camera, 1920, 1080);
    std::vector<std::uint8_t> png = encode_png(image);
    benchmark::DoNotOptimize(png.data());
  }
}
BENCHMARK(BM_ColdSnapshotToPng)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_EncodePng1080p(benchmark::State& state) {
  TubeScene tube(100000, true);
  const Camera camera = fit_camera(scene_bounds(tube.scene), 1920.0f / 1080.0f);
  const Image image = gl().renderer.render(tube.scene, camera, 1920, 1080);
  for (auto _ : state) {
    std::vector<std::uint8_t> png = encode_png(image);
    benchmark::DoNotOptimize(png.data());
  }
}
BENCHMARK(BM_EncodePng1080p)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace sutura::render

BENCHMARK_MAIN();
