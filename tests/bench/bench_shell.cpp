// Shell simulator benchmarks (issue 3): time to solution of the Sze 3.1 cantilever, one Newton
// iteration (assembly + factorisation + solve) at 1k-80k elements with memory, one implicit
// dynamics step at 5k elements, and the linear solvers compared on the same system.
// Run: build/tests/bench/bench_shell   (record the table in docs/performance.md)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "sutura/app/blas_restart.hpp"
#include "sutura/engine/blas_kernels.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/dynamics.hpp"
#include "sutura/engine/sim/selection.hpp"
#include "sutura/engine/sim/static_solver.hpp"
#include "sutura/engine/sim/tangent_assembler.hpp"

using namespace sutura::engine;

namespace {

double rss_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096.0 / (1024.0 * 1024.0);
}

// A vessel-like tube (radius 4 mm, wall 1 mm, E 1 MPa) clamped at z = 0, pulled sideways at
// the far end, with about `elements` faces.
struct TubeCase {
  SurfaceMesh mesh;
  std::vector<FaceIndices> faces;
  RestState rest;
  std::vector<ShellMaterial> materials{ShellMaterial{}};
  std::vector<int> face_material;
  std::unique_ptr<ShellModel> model;
  ShellSystem sys;
  ShellState state;

  TubeCase(int elements, std::unique_ptr<ShellModel> m) : model(std::move(m)) {
    const int around = std::max(8, static_cast<int>(std::sqrt(elements / 2.0)));
    const int along = std::max(1, elements / (2 * around));
    mesh = make_tube({4.0, 40.0, around, along});
    faces = mesh.faces();
    state = state_from_mesh(mesh);
    rest = rest_from_state(mesh, state);
    face_material.assign(faces.size(), 0);
    sys.model = model.get();
    sys.problem = ShellProblem{&faces, &rest, &materials, &face_material, mesh.num_vertices()};
    const auto root = select_vertices(mesh.positions(), SelectPlaneBand{Vec3(0, 0, 0), Vec3(0, 0, 1), 1e-9});
    sys.constraints.fix(root, kAllDofs, mesh.num_vertices());
    const auto tip = select_vertices(mesh.positions(), SelectPlaneBand{Vec3(0, 0, 40), Vec3(0, 0, 1), 1e-9});
    for (auto v : tip) sys.loads.nodal.push_back({v.index(), Vec3(0.01 / tip.size(), 0, 0), Vec3::Zero()});
  }
};

void BM_NewtonIteration(benchmark::State& st) {
  TubeCase c(static_cast<int>(st.range(0)), make_corotational_shell());
  const DofMap map(c.sys);
  auto solver = make_linear_solver(static_cast<LinearSolverKind>(st.range(1)));
  TangentAssembler assembler;
  Eigen::VectorXd du;
  // Steady state of a Newton loop: pattern and symbolic factorisation exist already.
  solver->factorize(evaluate(c.sys, map, c.state, 1.0, true, true, &assembler).tangent);
  for (auto _ : st) {
    Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true, true, &assembler);
    solver->factorize(ev.tangent);
    solver->solve(-ev.residual, du);
    benchmark::DoNotOptimize(du.data());
  }
  Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true);
  st.counters["elements"] = static_cast<double>(c.faces.size());
  st.counters["dofs"] = static_cast<double>(map.num_free());
  st.counters["nnz"] = static_cast<double>(ev.tangent.nonZeros());
  st.counters["rss_MB"] = rss_mb();
  st.SetLabel(to_string(static_cast<LinearSolverKind>(st.range(1))));
}

void BM_Assembly(benchmark::State& st) {
  TubeCase c(static_cast<int>(st.range(0)), make_corotational_shell());
  const DofMap map(c.sys);
  TangentAssembler assembler;
  evaluate(c.sys, map, c.state, 1.0, true, true, &assembler);
  for (auto _ : st) {
    Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true, true, &assembler);
    benchmark::DoNotOptimize(ev.tangent.valuePtr());
  }
  st.counters["elements"] = static_cast<double>(c.faces.size());
}

// The first assembly of a run: with a fresh assembler, so the sparsity pattern and the
// entry-to-triplet map are built too (once per solve without a SolverWorkspace, once per
// relaxation with one).
void BM_FirstAssembly(benchmark::State& st) {
  TubeCase c(static_cast<int>(st.range(0)), make_corotational_shell());
  const DofMap map(c.sys);
  for (auto _ : st) {
    TangentAssembler assembler;
    Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true, true, &assembler);
    benchmark::DoNotOptimize(ev.tangent.valuePtr());
  }
  st.counters["elements"] = static_cast<double>(c.faces.size());
}

// The two parts of a modified-Newton iteration with a factorisation already in hand: energy and
// gradient (no tangent), and one back-substitution. Gradient arguments: elements; 0 = model 1
// (corotational shell), 1 = model 2 (discrete shell).
void BM_Gradient(benchmark::State& st) {
  const bool discrete = st.range(1) == 1;
  TubeCase c(static_cast<int>(st.range(0)),
             discrete ? make_discrete_shell() : make_corotational_shell());
  const DofMap map(c.sys);
  for (auto _ : st) {
    Evaluation ev = evaluate(c.sys, map, c.state, 1.0, false);
    benchmark::DoNotOptimize(ev.residual.data());
  }
  st.counters["elements"] = static_cast<double>(c.faces.size());
  st.SetLabel(discrete ? "discrete shell" : "corotational shell");
}

// Argument 2: 0 = the exact solve, 1 = solve_approximately (the factor in single precision);
// the counter gives the approximate solve's relative error against the exact one.
void BM_BackSubstitution(benchmark::State& st) {
  TubeCase c(static_cast<int>(st.range(0)), make_corotational_shell());
  const DofMap map(c.sys);
  auto solver = make_linear_solver(LinearSolverKind::Cholmod);
  const Evaluation ev = evaluate(c.sys, map, c.state, 1.0, true);
  solver->factorize(ev.tangent);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(ev.tangent.rows());
  const bool approximate = st.range(1) == 1;
  Eigen::VectorXd x, exact;
  solver->solve(b, exact);
  for (auto _ : st) {
    if (approximate) solver->solve_approximately(b, x);
    else solver->solve(b, x);
    benchmark::DoNotOptimize(x.data());
  }
  st.counters["elements"] = static_cast<double>(c.faces.size());
  st.counters["relative_error"] = (x - exact).norm() / exact.norm();
}

// One run of 50 implicit steps (dt 1 ms) from rest: the tube swings under its tip load; the
// counters give the time per step including the first factorisation, the mean and the median
// time of steps 10 to 49 (the mean with the refactorisations among them, the median a step
// without one), and the tip's displacement (to compare the accuracy of the schemes and
// tolerances). Arguments: Newton tolerance per step as -log10 (6 = the default 1e-6); 1 =
// single-precision solves on reused matrices (the default), 0 = every solve exact; third:
// 0 = model 1 (corotational shell), 1 = model 2 (discrete shell, 3 DOF per node); fourth:
// 0 = DynamicsScheme::Newton, 1 = DynamicsScheme::Linearized (the default).
void BM_DynamicsStep(benchmark::State& st) {
  const bool discrete = st.range(2) == 1;
  TubeCase c(5000, discrete ? make_discrete_shell() : make_corotational_shell());
  DynamicsParams p;
  p.dt = 1e-3;
  p.steps = 50;
  p.tolerance = std::pow(10.0, -static_cast<double>(st.range(0)));
  p.single_precision_solves = st.range(1) == 1;
  p.scheme = st.range(3) == 1 ? DynamicsScheme::Linearized : DynamicsScheme::Newton;
  const auto tip = select_vertices(c.mesh.positions(), SelectNearest{{Vec3(4, 0, 40)}})[0].index();
  int newton = 0, steps = 0, factorizations = 0;
  double tip_ux = 0.0, steady_seconds = 0.0;
  using Clock = std::chrono::steady_clock;
  Clock::time_point from_step_10, last_mark;
  std::vector<double> step_seconds;  // steps 10 to 48, each
  // Steps 10 to 49 timed apart: a step of a running simulation, without the first
  // factorisation (with the ordering and the pattern) and the start from rest.
  const StepHook mark = [&](int step) {
    const Clock::time_point now = Clock::now();
    if (step == 10) from_step_10 = now;
    if (step > 10) step_seconds.push_back(std::chrono::duration<double>(now - last_mark).count());
    last_mark = now;
    return true;
  };
  for (auto _ : st) {
    DynamicsState s{c.state, {}};
    const DynamicsResult r = simulate_dynamics(c.sys, s, p, mark);
    steady_seconds += std::chrono::duration<double>(Clock::now() - from_step_10).count();
    newton += r.newton_iterations;
    steps += r.steps_done;
    factorizations += r.factorizations;
    tip_ux = s.shell.x[tip].x() - c.state.x[tip].x();
  }
  st.counters["elements"] = static_cast<double>(c.faces.size());
  st.counters["newton_per_step"] = static_cast<double>(newton) / std::max(steps, 1);
  st.counters["factorizations_per_run"] =
      static_cast<double>(factorizations) / std::max<double>(st.iterations(), 1);
  st.counters["tip_ux_um"] = 1e3 * tip_ux;
  st.counters["ms_per_step_10_to_50"] =
      1e3 * steady_seconds / std::max<double>(st.iterations(), 1) / (p.steps - 10);
  if (!step_seconds.empty()) {
    auto middle = step_seconds.begin() + static_cast<std::ptrdiff_t>(step_seconds.size() / 2);
    std::nth_element(step_seconds.begin(), middle, step_seconds.end());
    st.counters["ms_median_step"] = 1e3 * *middle;
  }
  st.SetLabel(std::string(discrete ? "discrete shell" : "corotational shell") +
              (p.scheme == DynamicsScheme::Linearized ? ", linearized" : ""));
}

// Sze, Liu & Lo 2004 case 3.1 from the unloaded strip to equilibrium at P = 4.
void BM_SzeCantilever(benchmark::State& st) {
  const int nl = static_cast<int>(st.range(0)), nw = static_cast<int>(st.range(1));
  const int steps = static_cast<int>(st.range(2));
  double ux = 0.0, uz = 0.0;
  int iterations = 0;
  for (auto _ : st) {
    SurfaceMesh mesh = make_strip({10.0, 1.0, nl, nw});
    std::vector<FaceIndices> faces = mesh.faces();
    ShellState state = state_from_mesh(mesh);
    RestState rest = rest_from_state(mesh, state);
    ShellMaterial mat;
    mat.youngs_modulus = 1.2e6;
    mat.poisson_ratio = 0.0;
    mat.thickness = 0.1;
    std::vector<ShellMaterial> mats{mat};
    std::vector<int> fm(faces.size(), 0);
    auto model = make_corotational_shell();
    ShellSystem sys;
    sys.model = model.get();
    sys.problem = ShellProblem{&faces, &rest, &mats, &fm, mesh.num_vertices()};
    sys.constraints.fix(select_vertices(mesh.positions(), SelectPlaneBand{Vec3(0, 0, 0), Vec3(1, 0, 0), 1e-9}),
                        kAllDofs, mesh.num_vertices());
    const auto tip = select_vertices(mesh.positions(), SelectPlaneBand{Vec3(10, 0, 0), Vec3(1, 0, 0), 1e-9});
    // Consistent line load P/b along the tip edge: end nodes get half a segment's share.
    const double seg = 1.0 / nw;
    for (std::size_t i = 0; i < tip.size(); ++i) {
      const double w = (i == 0 || i + 1 == tip.size()) ? 0.5 * seg : seg;
      sys.loads.nodal.push_back({tip[i].index(), Vec3(0, 0, 4.0 * w), Vec3::Zero()});
    }
    StaticSolverParams p;
    p.load_steps = steps;
    p.tolerance = 1e-6;
    const StaticResult r = solve_static(sys, state, p);
    const auto v = select_vertices(mesh.positions(), SelectNearest{{Vec3(10, 0, 0)}})[0];
    ux = state.x[v.index()].x() - 10.0;
    uz = state.x[v.index()].z();
    iterations = r.iterations;
  }
  st.counters["minus_u"] = -ux;
  st.counters["w"] = uz;
  st.counters["err_u_pct"] = 100.0 * std::abs(-ux - 3.286) / 3.286;
  st.counters["err_w_pct"] = 100.0 * std::abs(uz - 6.698) / 6.698;
  st.counters["newton"] = iterations;
}

}  // namespace

BENCHMARK(BM_SzeCantilever)->Args({16, 1, 4})->Args({32, 2, 4})->Args({64, 2, 4})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Assembly)->Arg(1000)->Arg(5000)->Arg(20000)->Arg(80000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FirstAssembly)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NewtonIteration)
    ->Args({1000, 0})->Args({5000, 0})->Args({20000, 0})->Args({80000, 0})
    ->Args({20000, 1})->Args({20000, 2})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Gradient)
    ->Args({5000, 0})
    ->Args({20000, 0})
    ->Args({5000, 1})
    ->Args({20000, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BackSubstitution)
    ->Args({5000, 0})
    ->Args({5000, 1})
    ->Args({20000, 0})
    ->Args({20000, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DynamicsStep)
    ->Args({6, 1, 0, 0})
    ->Args({6, 0, 0, 0})
    ->Args({4, 1, 0, 0})
    ->Args({3, 1, 0, 0})
    ->Args({6, 1, 1, 0})
    ->Args({6, 1, 0, 1})
    ->Args({6, 1, 1, 1})
    ->Unit(benchmark::kMillisecond);
int main(int argc, char** argv) {
  // The same OpenBLAS kernels as the sutura program uses (why: blas_kernels.hpp).
  sutura::app::restart_with_better_blas_kernels(argv);
  benchmark::AddCustomContext("blas", sutura::engine::blas_kernels_in_use());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
