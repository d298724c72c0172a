// Patient data (issue 23): `prepare_vessel` of the synthetic segmentation export of the
// bundled arch (the fine arch closed by flat caps, subdivided, noise of 7 % of its edge along
// the normals), at about 78k faces (mean edge 0.25 mm, as `generate arch --as-segmentation`
// writes it) and about 1.24M faces (0.065 mm; the target: at most 30 s and 4 GB). The input
// is built once, outside the timing; loading the STL is not timed (docs/performance.md gives
// the whole command, load included, with its peak memory).
// Also `extract_centreline` (the automatic centreline; target: at most 2 s at 20k faces) on
// the fine arch (19k faces) and on the prepared 78k-face export (17k faces).
// Run: build/tests/bench/bench_prepare --benchmark_repetitions=3   (record the medians in
// docs/performance.md)
#include <benchmark/benchmark.h>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/anatomy/segmentation_export.hpp"
#include "sutura/engine/measure/centreline.hpp"
#include "sutura/engine/patient/prepare.hpp"

using namespace sutura::engine;

namespace {

const SurfaceMesh& fine_arch() {
  static const SurfaceMesh aorta = [] {
    ArchParams p;
    p.target_edge_length = kArchFineEdgeLength;
    return generate_arch(p).aorta;
  }();
  return aorta;
}

// Args: the export's largest mean edge in micrometres (300: ~78k faces; 100: ~1.24M faces);
// 1: the default coarsening (in two halves from 200k faces), 0: in one pass whatever the size
// (the A/B of the halves).
void BM_Prepare(benchmark::State& state) {
  SegmentationLikeParams sp;
  sp.max_edge_length = static_cast<double>(state.range(0)) * 1e-3;
  sp.noise = 0.07 * sp.max_edge_length;
  const SurfaceMesh input = segmentation_like(fine_arch(), sp);
  PrepareResult result;
  for (auto _ : state) {
    PrepareParams params;
    if (state.range(1) == 0) params.coarsen_in_halves_from = input.num_faces() + 1;
    result = prepare_vessel(input, params);
    benchmark::DoNotOptimize(result.vessel.num_faces());
  }
  state.counters["input_faces"] = static_cast<double>(input.num_faces());
  state.counters["output_faces"] = static_cast<double>(result.vessel.num_faces());
  state.counters["min_angle_deg"] = result.min_angle_deg;
  state.counters["hausdorff_pct_of_edge"] = 100.0 * result.to_input.symmetric / result.edge_length;
  for (const auto& [step, seconds] : result.step_seconds) state.counters[step + "_s"] = seconds;
}

// Arg 0: the fine arch with its generator's ends; 1: the prepared 78k-face export, ends as
// prepare found them.
void BM_Centreline(benchmark::State& state) {
  ArchParams p;
  p.target_edge_length = kArchFineEdgeLength;
  ArchAnatomy arch = generate_arch(p);
  SurfaceMesh vessel = arch.aorta;
  std::vector<VesselEnd> ends = arch.landmarks.aorta_ends;
  if (state.range(0) == 1) {
    SegmentationLikeParams sp;
    sp.noise = 0.07 * sp.max_edge_length;
    PrepareResult prepared = prepare_vessel(segmentation_like(fine_arch(), sp));
    vessel = std::move(prepared.vessel);
    ends.clear();
    for (const PreparedEnd& e : prepared.ends) ends.push_back(e.end);
  }
  CentrelineTree tree;
  for (auto _ : state) {
    tree = extract_centreline(vessel, ends);
    benchmark::DoNotOptimize(tree.points.size());
  }
  state.counters["faces"] = static_cast<double>(vessel.num_faces());
  state.counters["points"] = static_cast<double>(tree.points.size());
  state.counters["branch_points"] = static_cast<double>(tree.branch_points.size());
}

}  // namespace

BENCHMARK(BM_Centreline)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Prepare)->Args({300, 1})->Args({100, 1})->Args({100, 0})->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
