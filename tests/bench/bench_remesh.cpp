// Surgical remeshing benchmarks (issue 22): one cut-through incision on the bundled arches
// (coarse ~4k, fine ~19k faces) with and without the band remesh (their difference is the
// local remesh's cost), and the remesh alone of a band of two edge lengths around a 13 mm
// curve at 20k faces. The incision is the default session's (patch aortoplasty).
// Run: build/tests/bench/bench_remesh   (record the table in docs/performance.md)
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "sutura/engine/mesh_io.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/remesh.hpp"

using namespace sutura::engine;

namespace {

const SurfaceMesh& arch(bool fine) {
  static const SurfaceMesh coarse = load_mesh(std::string(SUTURA_ASSETS_DIR) + "/anatomy/coarse/aorta.ply");
  static const SurfaceMesh dense = load_mesh(std::string(SUTURA_ASSETS_DIR) + "/anatomy/fine/aorta.ply");
  return fine ? dense : coarse;
}

const std::vector<Vec3> kCurve{{11.304, 11.539, 22.511}, {12.114, 13.147, 20.671},
                               {11.737, 14.239, 18.269}, {13.149, 14.706, 15.915},
                               {13.539, 14.745, 13.599}, {13.574, 14.745, 11.399}};

// Arg 0: 0 = coarse, 1 = fine; arg 1: 1 = band remesh (the default), 0 = the raw trace.
void BM_Incise(benchmark::State& state) {
  const SurfaceMesh& m = arch(state.range(0) == 1);
  IncisionParams p;
  p.remesh = state.range(1) == 1;
  IncisionResult r;
  for (auto _ : state) {
    r = incise(m, kCurve, p);
    benchmark::DoNotOptimize(r.mesh.num_faces());
  }
  state.counters["faces"] = double(m.num_faces());
  if (r.remeshed) state.counters["band_min_angle"] = r.band_after.min_angle_deg;
}
BENCHMARK(BM_Incise)->Args({0, 0})->Args({0, 1})->Args({1, 0})->Args({1, 1})->Unit(benchmark::kMillisecond);

// The remesh alone: the band of two edge lengths around the curve's chord polyline on the
// fine arch, uniform at its own spacing.
void BM_RemeshBand(benchmark::State& state) {
  const SurfaceMesh& m = arch(true);
  RemeshParams p;
  p.target_edge_length = mean_edge_length(m);
  p.region = faces_near_polyline(m, kCurve, 2.0 * p.target_edge_length);
  RemeshResult r;
  for (auto _ : state) {
    r = remesh(m, p);
    benchmark::DoNotOptimize(r.mesh.num_faces());
  }
  state.counters["faces"] = double(m.num_faces());
  state.counters["band_faces"] = double(p.region->size());
  state.counters["band_min_angle"] = r.after.min_angle_deg;
}
BENCHMARK(BM_RemeshBand)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
