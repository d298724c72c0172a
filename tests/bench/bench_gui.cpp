// GUI benchmark (not a test): picking time on a 100,000-triangle mesh, and the frame time of
// the real window with a 20,000-triangle mesh and the UI open, the pointer over the mesh
// (hover picking every frame). Needs an X display: under Xvfb run
//   xvfb-run -s "-screen 0 1600x1000x24" build/tests/bench/bench_gui
// Prints a table; targets: picking < 5 ms, >= 30 frames per second (docs/performance.md).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "../../ui/src/scene_picker.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/ui/gui.hpp"
#include "sutura/ui/orbit_camera.hpp"

namespace fs = std::filesystem;
using namespace sutura;
using clock_type = std::chrono::steady_clock;

namespace {

double ms_since(clock_type::time_point t) {
  return std::chrono::duration<double, std::milli>(clock_type::now() - t).count();
}

void bench_picking() {
  engine::TubeParams p;
  p.segments_around = 250;
  p.segments_along = 200;  // 2 * 250 * 200 = 100,000 triangles
  const engine::SurfaceMesh tube = engine::make_tube(p);
  auto t0 = clock_type::now();
  ui::ScenePicker picker;
  picker.rebuild({&tube});
  const double build_ms = ms_since(t0);
  ui::OrbitCamera cam;
  const auto b = tube.bounds();
  cam.fit({{{float(b.min().x()), float(b.min().y()), float(b.min().z())},
            {float(b.max().x()), float(b.max().y()), float(b.max().z())}}},
          1.5f);
  // Half the rays through random pixels (mostly background), half at random faces.
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> px(0.0f, 1200.0f), py(0.0f, 800.0f);
  std::uniform_int_distribution<std::size_t> face(0, tube.num_faces() - 1);
  const int n = 4000;
  int hits = 0;
  double worst = 0.0, total = 0.0;
  for (int i = 0; i < n; ++i) {
    std::array<float, 2> pixel = {px(rng), py(rng)};
    // Every other ray aims at a face centroid (the tube is in view: project succeeds).
    if (i % 2 == 1)
      static_cast<void>(
          cam.project(tube.face_centroid(engine::FaceId(face(rng))), 1200, 800, pixel));
    const auto t = clock_type::now();
    if (picker.pick(cam.ray_through(pixel[0], pixel[1], 1200, 800))) ++hits;
    const double ms = ms_since(t);
    total += ms;
    worst = std::max(worst, ms);
  }
  const double mean = total / n;
  std::printf("| picking, %zu triangles | BVH build %.1f ms | pick mean %.4f ms, max %.4f ms (%d of %d rays hit) |\n",
              tube.num_faces(), build_ms, mean, worst, hits, n);
}

void bench_frames() {
  const fs::path dir = fs::temp_directory_path() / "sutura_bench_gui";
  fs::create_directories(dir);
  std::ofstream(dir / "mesh.jsonl")
      << "{\"format\": \"sutura-session\", \"version\": 1}\n"
      << "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30, "
         "\"segments_around\": 100, \"segments_along\": 100}\n";  // 20,000 triangles
  std::ofstream(dir / "script.jsonl") << "{\"wait_frames\": 20}\n{\"move\": [900, 450]}\n"
                                      << "{\"wait_frames\": 10}\n{\"time_frames\": 300}\n{\"quit\": true}\n";
  ui::GuiOptions o;
  o.session = dir / "mesh.jsonl";
  o.out_dir = dir / "out";
  o.script = dir / "script.jsonl";
  std::printf("| window 1400x900, 20,000 triangles, UI open, hover picking | ");
  std::fflush(stdout);
  ui::run_gui(o);  // prints the frame statistics line
  fs::remove_all(dir);
}

}  // namespace

int main() {
  bench_picking();
  bench_frames();
  return 0;
}
