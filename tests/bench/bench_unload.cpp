// Unloaded reference geometry (issue 23): `unload` of the bundled arch taken as imaged at
// 80 mmHg, against one pressurised solve of the same arch from its stress-free shape (the
// target: unload within 3 times that). Both with the bundled sessions' settings (energy
// minimisation, one load step, a new tangent after at most 5 quasi-Newton steps), five held
// ends, wall 0.6 mm, E 1 MPa, nu 0.45.
// Run: build/tests/bench/bench_unload --benchmark_repetitions=5   (record medians and the
// ratio in docs/performance.md)
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "sutura/engine/mesh_io.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/unload.hpp"

using namespace sutura::engine;

namespace {

struct Arch {
  SurfaceMesh mesh;
  std::vector<FaceIndices> faces;
  RestState rest;
  std::vector<ShellMaterial> materials{ShellMaterial{}};
  std::vector<int> face_material;
  std::unique_ptr<ShellModel> model = make_corotational_shell();
  ShellSystem sys;
  StaticSolverParams solver;

  explicit Arch(bool fine)
      : mesh(load_mesh(std::string(SUTURA_ASSETS_DIR) + (fine ? "/anatomy/fine/aorta.ply"
                                                              : "/anatomy/coarse/aorta.ply"))) {
    faces = mesh.faces();
    rest = rest_from_state(mesh, state_from_mesh(mesh));
    face_material.assign(faces.size(), 0);
    materials[0].youngs_modulus = 1.0;
    materials[0].poisson_ratio = 0.45;
    materials[0].thickness = 0.6;
    sys.model = model.get();
    sys.problem = ShellProblem{&faces, &rest, &materials, &face_material, mesh.num_vertices()};
    std::vector<VertexId> rims;
    for (const auto& loop : mesh.boundary_loops()) rims.insert(rims.end(), loop.begin(), loop.end());
    sys.constraints.fix(rims, kAllDofs, mesh.num_vertices());
    sys.loads.pressures.push_back({{}, 0.0107});
    solver.shift_indefinite = true;
    solver.quasi_newton_steps = 5;
  }
};

Arch& arch(bool fine) {
  static Arch coarse(false);
  static Arch dense(true);
  return fine ? dense : coarse;
}

// Arg: 0 = coarse (~4.5k faces), 1 = fine (~19k faces).
void BM_PressurisedSolve(benchmark::State& state) {
  Arch& a = arch(state.range(0) == 1);
  StaticResult r;
  for (auto _ : state) {
    ShellState s = state_from_mesh(a.mesh);
    SolverWorkspace ws;
    r = solve_static(a.sys, s, a.solver, &ws);
    benchmark::DoNotOptimize(s.x.data());
  }
  state.counters["faces"] = double(a.faces.size());
  state.counters["solver_iterations"] = r.iterations + r.quasi_newton_iterations;
  if (!r.converged) state.SkipWithError(r.message.c_str());
}
BENCHMARK(BM_PressurisedSolve)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_Unload(benchmark::State& state) {
  Arch& a = arch(state.range(0) == 1);
  UnloadParams p;
  p.solver = a.solver;
  UnloadResult r;
  for (auto _ : state) {
    SolverWorkspace ws;
    r = unload(a.sys, a.mesh.positions(), p, &ws);
    benchmark::DoNotOptimize(r.state.x.data());
  }
  state.counters["faces"] = double(a.faces.size());
  state.counters["forward_solves"] = double(r.history.size());
  state.counters["solver_iterations"] = r.solver_iterations;
  state.counters["max_deviation_um"] = 1e3 * r.max_deviation;
  if (!r.converged) state.SkipWithError(r.message.c_str());
}
BENCHMARK(BM_Unload)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
