#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sim_fixture.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/static_solver.hpp"

using namespace sutura::engine;
using sutura::engine::testing::Cantilever;

TEST(StaticSolver, LinearAnalysisMatchesBeamTheory) {
  // P L^3 / (3 E I) with I = b t^3 / 12 = 1e-4/1.2: 1e-3 * 1000 / (3 * 100) = 3.333e-3.
  Cantilever c(make_corotational_shell(), 1e-3);
  StaticSolverParams p;
  p.linear = true;
  const StaticResult r = solve_static(c.sys, c.state, p);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.iterations, 1);
  EXPECT_NEAR(c.tip_displacement().z(), 1e-3 * 1000.0 / 300.0, 0.01 * 1e-3 * 1000.0 / 300.0);
}

TEST(StaticSolver, NewtonConvergesQuadraticallyWithLoadSteps) {
  Cantilever c(make_corotational_shell(), 4.0);  // Sze case 3.1 load
  StaticSolverParams p;
  p.load_steps = 4;
  const StaticResult r = solve_static(c.sys, c.state, p);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_DOUBLE_EQ(r.lambda_reached, 1.0);
  // Within the last load step: the residual falls faster than linearly near the solution
  // (r_{k+1} <= r_k^1.5 once r_k is small relative to the first residual of the step).
  std::vector<double> last;
  for (const auto& h : r.history)
    if (h.lambda == 1.0) last.push_back(h.residual);
  ASSERT_GE(last.size(), 3u);
  const double r0 = last.front();
  int checked = 0;
  for (std::size_t k = 1; k + 1 < last.size(); ++k) {
    const double a = last[k] / r0, b = last[k + 1] / r0;
    if (a < 1e-2 && b > 1e-14) {
      EXPECT_LT(b, std::pow(a, 1.5)) << "iteration " << k;
      ++checked;
    }
  }
  EXPECT_GE(checked, 1);
  // Large deflection: the tip moves back (u < 0) and up well beyond the linear regime.
  EXPECT_LT(c.tip_displacement().x(), -2.0);
  EXPECT_GT(c.tip_displacement().z(), 5.0);
}

// keep_going is asked before every iteration; its first "no" ends the solve at once: no step
// cut, no retry (each would ask again), the state rolled back to the last converged load step.
TEST(StaticSolver, KeepGoingStopsTheSolveWithoutCutsOrRetries) {
  for (const bool minimise : {false, true}) {
    SCOPED_TRACE(minimise ? "energy minimisation" : "Newton");
    Cantilever reference(make_corotational_shell(), 4.0), c(make_corotational_shell(), 4.0);
    StaticSolverParams p;
    p.load_steps = 4;
    p.shift_indefinite = minimise;
    StaticSolverParams first_step = p;
    first_step.lambda_end = 0.25;
    first_step.load_steps = 1;
    ASSERT_TRUE(solve_static(reference.sys, reference.state, first_step).converged);
    // The "no" comes in the second load step, after its first iteration.
    int asked = 0, asked_in_first_step = -1;
    p.keep_going = [&] { return ++asked != asked_in_first_step + 2; };
    StaticSolverParams probe = first_step;
    probe.keep_going = [&] { ++asked_in_first_step; return true; };
    Cantilever counter(make_corotational_shell(), 4.0);
    ASSERT_TRUE(solve_static(counter.sys, counter.state, probe).converged);
    const StaticResult r = solve_static(c.sys, c.state, p);
    EXPECT_FALSE(r.converged);
    EXPECT_TRUE(r.stopped);
    EXPECT_EQ(asked, asked_in_first_step + 2);  // never asked again after the "no"
    EXPECT_DOUBLE_EQ(r.lambda_reached, 0.25);
    EXPECT_NE(r.message.find("stopped by the caller"), std::string::npos) << r.message;
    ASSERT_EQ(c.state.x.size(), reference.state.x.size());
    for (std::size_t i = 0; i < c.state.x.size(); ++i) EXPECT_EQ(c.state.x[i], reference.state.x[i]);
  }
}

TEST(StaticSolver, ContinuesFromAnIntermediateLoadFactor) {
  Cantilever a(make_corotational_shell(), 2.0), b(make_corotational_shell(), 2.0);
  StaticSolverParams p;
  p.load_steps = 2;
  ASSERT_TRUE(solve_static(a.sys, a.state, p).converged);
  StaticSolverParams half = p;
  half.lambda_end = 0.5;
  half.load_steps = 1;
  ASSERT_TRUE(solve_static(b.sys, b.state, half).converged);
  StaticSolverParams rest = p;
  rest.lambda_start = 0.5;
  rest.load_steps = 1;
  ASSERT_TRUE(solve_static(b.sys, b.state, rest).converged);
  EXPECT_LT((a.tip_displacement() - b.tip_displacement()).norm(), 1e-6 * a.tip_displacement().norm());
}

TEST(StaticSolver, ResolvesUnderLoadsAlreadyAppliedFromAPerturbedState) {
  // After an edit the loads stay at full value (fixed_loads) and nothing new is ramped in:
  // the divergence check must take its energy reference from those loads, not from the
  // (empty) new ones, or any strain energy looks like a blow-up.
  Cantilever c(make_corotational_shell(), 2.0);
  StaticSolverParams p;
  p.load_steps = 2;
  ASSERT_TRUE(solve_static(c.sys, c.state, p).converged);
  const Vec3 reference = c.tip_displacement();
  c.sys.fixed_loads = c.sys.loads;
  c.sys.loads = Loads{};
  for (std::size_t v = 0; v < c.state.x.size(); ++v)
    if (!c.sys.constraints.is_fixed(v, 0)) c.state.x[v].z() *= 0.8;
  StaticSolverParams again;
  const StaticResult r = solve_static(c.sys, c.state, again);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LT((c.tip_displacement() - reference).norm(), 1e-6 * reference.norm());
}

TEST(StaticSolver, SettlesAPrestressedBodyWithoutLoads) {
  // Both ends clamped, the rest shape shrunk by 10 %: a stressed start with no load at all (as a
  // sutured vessel settling after a remesh). Its strain energy is the divergence check's
  // reference; with the loads' work alone (zero) the first iterate read as an explosion.
  for (const bool minimise : {false, true}) {
    SCOPED_TRACE(minimise ? "energy minimisation" : "Newton");
    Cantilever c(make_corotational_shell(), 0.0);
    c.sys.loads = Loads{};
    const auto tip = select_vertices(c.mesh.positions(), SelectPlaneBand{Vec3(10, 0, 0), Vec3(1, 0, 0), 1e-9});
    c.sys.constraints.fix(tip, kAllDofs, c.mesh.num_vertices());
    for (ElementRest& e : c.rest.elements)
      for (Vec3& X : e.X) X *= 0.9;
    const double start = evaluate(c.sys, DofMap(c.sys), c.state, 0.0, false).internal_energy;
    ASSERT_GT(start, 0.0);
    StaticSolverParams p;
    p.shift_indefinite = minimise;
    const StaticResult r = solve_static(c.sys, c.state, p);
    ASSERT_TRUE(r.converged) << r.message;
    // With nu = 0 the energy is E t / 2 (ex^2 + ey^2) per area, half of it in each direction:
    // the free long edges draw in and release ey, except near the clamps (measured 0.533).
    EXPECT_GT(r.energy, 0.5 * start);
    EXPECT_LT(r.energy, 0.56 * start);
  }
}

TEST(StaticSolver, UnconstrainedStructureFailsAndRollsBack) {
  Cantilever c(make_corotational_shell(), 1.0);
  c.sys.constraints.fixed.clear();
  const ShellState before = c.state;
  StaticSolverParams p;
  p.max_step_cuts = 1;
  const StaticResult r = solve_static(c.sys, c.state, p);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("rolled back"), std::string::npos) << r.message;
  EXPECT_EQ(r.lambda_reached, 0.0);
  for (std::size_t i = 0; i < before.x.size(); ++i) EXPECT_EQ(before.x[i], c.state.x[i]);
}

TEST(StaticSolver, NonFiniteLoadIsDetected) {
  Cantilever c(make_corotational_shell(), 1.0);
  c.sys.loads.nodal[0].force.z() = std::numeric_limits<double>::quiet_NaN();
  const ShellState before = c.state;
  StaticSolverParams p;
  p.max_step_cuts = 0;
  const StaticResult r = solve_static(c.sys, c.state, p);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("non-finite"), std::string::npos) << r.message;
  for (std::size_t i = 0; i < before.x.size(); ++i) EXPECT_EQ(before.x[i], c.state.x[i]);
}

TEST(StaticSolver, LinearSolversAgree) {
  double reference = 0.0;
  for (auto kind : {LinearSolverKind::Cholmod, LinearSolverKind::Ldlt, LinearSolverKind::Pcg}) {
    Cantilever c(make_corotational_shell(), 1.0);
    StaticSolverParams p;
    p.load_steps = 2;
    p.linear_solver = kind;
    const StaticResult r = solve_static(c.sys, c.state, p);
    ASSERT_TRUE(r.converged) << to_string(kind) << ": " << r.message;
    const double w = c.tip_displacement().z();
    if (kind == LinearSolverKind::Cholmod) reference = w;
    EXPECT_NEAR(w, reference, 1e-6 * std::abs(reference)) << to_string(kind);
  }
}

TEST(StaticSolver, AWorkspaceCarriedAcrossSolvesGivesBitIdenticalResults) {
  // Two load steps solved as two calls sharing a workspace, against the same two calls each
  // with its own: the cached pattern and ordering must not change a single bit. Then the
  // workspace is handed a system of another structure (a finer strip; a Cholesky solve, then
  // a PCG one): it must notice and give again exactly what a fresh solve gives.
  Cantilever a(make_corotational_shell(), 4.0), b(make_corotational_shell(), 4.0);
  SolverWorkspace workspace;
  StaticSolverParams first;
  first.lambda_end = 0.5;
  StaticSolverParams second;
  second.lambda_start = 0.5;
  ASSERT_TRUE(solve_static(a.sys, a.state, first, &workspace).converged);
  ASSERT_TRUE(solve_static(a.sys, a.state, second, &workspace).converged);
  ASSERT_TRUE(solve_static(b.sys, b.state, first).converged);
  ASSERT_TRUE(solve_static(b.sys, b.state, second).converged);
  for (std::size_t i = 0; i < a.state.x.size(); ++i) {
    EXPECT_EQ(a.state.x[i], b.state.x[i]) << "vertex " << i;
    EXPECT_EQ(a.state.D[i].coeffs(), b.state.D[i].coeffs()) << "vertex " << i;
  }
  for (auto kind : {LinearSolverKind::Cholmod, LinearSolverKind::Pcg}) {
    Cantilever fine(make_corotational_shell(), 4.0, 32), alone(make_corotational_shell(), 4.0, 32);
    StaticSolverParams p;
    p.load_steps = 4;
    p.linear_solver = kind;
    ASSERT_TRUE(solve_static(fine.sys, fine.state, p, &workspace).converged) << to_string(kind);
    ASSERT_TRUE(solve_static(alone.sys, alone.state, p).converged) << to_string(kind);
    for (std::size_t i = 0; i < fine.state.x.size(); ++i)
      EXPECT_EQ(fine.state.x[i], alone.state.x[i]) << to_string(kind) << ", vertex " << i;
  }
}

TEST(StaticSolver, InflationStepsWithTheInternalTangentWhereThePressureMakesItIndefinite) {
  // A thin vessel-like tube (R 4 mm, wall 0.3 mm, E 1 MPa) held at both ends under
  // 80 mmHg: unstressed, its tangent is indefinite through the follower-pressure load
  // stiffness alone. The Cholesky solver must then step with the tangent of the internal
  // forces (a descent direction: the potential falls at the first iteration) and reach the
  // same equilibrium as LDL^T on the true tangent.
  struct HeldTube {
    SurfaceMesh mesh = make_tube({4.0, 20.0, 24, 24});
    std::vector<FaceIndices> faces = mesh.faces();
    ShellState state = state_from_mesh(mesh);
    RestState rest = rest_from_state(mesh, state);
    std::vector<ShellMaterial> materials{ShellMaterial{}};
    std::vector<int> face_material = std::vector<int>(faces.size(), 0);
    std::unique_ptr<ShellModel> model = make_corotational_shell();
    ShellSystem sys;
    HeldTube() {
      materials[0].youngs_modulus = 1.0;
      materials[0].poisson_ratio = 0.45;
      materials[0].thickness = 0.3;
      sys.model = model.get();
      sys.problem = ShellProblem{&faces, &rest, &materials, &face_material, mesh.num_vertices()};
      for (double z : {0.0, 20.0})
        sys.constraints.fix(select_vertices(mesh.positions(),
                                            SelectPlaneBand{Vec3(0, 0, z), Vec3(0, 0, 1), 1e-9}),
                            kAllDofs, mesh.num_vertices());
      sys.loads.pressures.push_back({{}, 0.0107});
    }
  };
  HeldTube chol, ldlt;
  const DofMap map(chol.sys);
  auto probe = make_linear_solver(LinearSolverKind::Cholmod);
  ASSERT_FALSE(probe->factorize_definite(evaluate(chol.sys, map, chol.state, 1.0, true).tangent))
      << "precondition: the tangent under pressure is indefinite at the start";
  ASSERT_TRUE(probe->factorize_definite(evaluate(chol.sys, map, chol.state, 1.0, true, false).tangent))
      << "precondition: the tangent of the internal forces is positive definite";
  StaticSolverParams p;
  const StaticResult a = solve_static(chol.sys, chol.state, p);
  ASSERT_TRUE(a.converged) << a.message;
  ASSERT_GE(a.history.size(), 2u);
  EXPECT_LT(a.history[1].potential, a.history[0].potential);
  p.linear_solver = LinearSolverKind::Ldlt;
  const StaticResult b = solve_static(ldlt.sys, ldlt.state, p);
  ASSERT_TRUE(b.converged) << b.message;
  double largest = 0.0, differ = 0.0;
  for (std::size_t i = 0; i < chol.state.x.size(); ++i) {
    largest = std::max(largest, (chol.state.x[i] - chol.mesh.position(VertexId(i))).norm());
    differ = std::max(differ, (chol.state.x[i] - ldlt.state.x[i]).norm());
  }
  EXPECT_GT(largest, 0.1);  // mm: the tube did inflate
  EXPECT_LT(differ, 1e-8 * largest);
  // The steps differ (the first residual after it too) and save an iteration here (4 vs 5;
  // on the fine arch 9 vs 12).
  EXPECT_NE(a.history[1].residual, b.history[1].residual);
  EXPECT_LT(a.iterations, b.iterations);
}

TEST(ShellSystem, MinAreaRatioComparesCurrentAndRestAreas) {
  Cantilever c(make_corotational_shell(), 0.0, 2, 1, 2.0, 1.0);  // 4 triangles of area 1/2
  EXPECT_DOUBLE_EQ(min_area_ratio(c.sys.problem, c.state), 1.0);
  ShellState squashed = c.state;
  // The strip spans y in [-0.5, 0.5]: move its corner (2, 0.5) to 1/100 of the width above the
  // opposite edge, so the triangles using it keep 1/100 of their height.
  const auto v = select_vertices(c.mesh.positions(), SelectNearest{{Vec3(2, 0.5, 0)}})[0];
  ASSERT_DOUBLE_EQ(c.state.x[v.index()].y(), 0.5);
  squashed.x[v.index()].y() = -0.49;
  EXPECT_NEAR(min_area_ratio(c.sys.problem, squashed), 0.01, 1e-12);
  ShellState moved = c.state;  // a rigid motion keeps every area
  const Eigen::AngleAxisd R(0.7, Vec3(1, 2, 3).normalized());
  for (Vec3& x : moved.x) x = R * x + Vec3(5, -2, 1);
  EXPECT_NEAR(min_area_ratio(c.sys.problem, moved), 1.0, 1e-12);
}

// A 1 x 1 mm square (two triangles) clamped on one side and pushed in its plane from the
// other: the flat corotational elements do not resist being squashed through zero area, so
// without the guard the solver "converges" at a load factor where a triangle keeps 0.8 % of
// its area. With the guard (default 1e-2) such trial states are rejected and the solve stops
// with a message naming the collapse, at a state with no collapsed triangle.
TEST(StaticSolver, TrialStatesThatCollapseATriangleAreRejected) {
  for (const double guard : {0.0, 1e-2}) {
    Cantilever c(make_corotational_shell(), 0.0, 1, 1, 1.0, 1.0, 0.1, 1.0);
    for (auto& l : c.sys.loads.nodal) l.force = Vec3(-0.025, 0.0, 0.0);
    StaticSolverParams p;
    p.min_area_ratio = guard;
    ShellState s = c.state;
    const StaticResult r = solve_static(c.sys, s, p);
    ASSERT_FALSE(r.converged);
    if (guard == 0.0) {
      EXPECT_LT(min_area_ratio(c.sys.problem, s), 0.01);  // why the guard exists
    } else {
      EXPECT_GE(min_area_ratio(c.sys.problem, s), 0.01);
      EXPECT_NE(r.message.find("collapsed a triangle"), std::string::npos) << r.message;
    }
  }
}

// With shift_indefinite the solver minimises the total potential energy, strain energy minus
// the work of the loads, and every accepted step must decrease it (Armijo), also when loads act:
// the Sze cantilever taken to its full load in one step, whose first Newton step (the linear
// predictor, a tip deflection of 13 L) multiplies the potential many times over.
TEST(StaticSolver, EnergyMinimisationDecreasesThePotentialUnderLoads) {
  Cantilever c(make_corotational_shell(), 4.0, 16, 1);
  StaticSolverParams p;
  p.shift_indefinite = true;
  p.max_iterations = 100;
  const StaticResult r = solve_static(c.sys, c.state, p);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_GE(r.history.size(), 3u);
  EXPECT_EQ(r.history.front().potential, r.history.front().energy);  // no work done yet
  for (std::size_t k = 1; k < r.history.size(); ++k)
    EXPECT_LE(r.history[k].potential, r.history[k - 1].potential + 1e-12) << "iteration " << k;
  // At equilibrium under the dead tip load the potential is negative (the load did more work
  // than the strip stores), and the answer is the one of the load-stepped analysis.
  EXPECT_LT(r.history.back().potential, 0.0);
  Cantilever stepped(make_corotational_shell(), 4.0, 16, 1);
  StaticSolverParams q;
  q.load_steps = 4;
  ASSERT_TRUE(solve_static(stepped.sys, stepped.state, q).converged);
  EXPECT_LT((c.tip_displacement() - stepped.tip_displacement()).norm(), 1e-6);
}

// Quasi-Newton steps (the default of an energy minimisation) reach the minimum the Newton-only
// iteration reaches, with fewer factorised tangents, and decrease the potential at every step.
// A load-stepped minimisation starts from the tangent at its start (in equilibrium there); one
// at a fixed load factor whose system changed (a relaxation increment) starts from the
// factorisation the workspace holds, if nothing else factorised since.
TEST(StaticSolver, QuasiNewtonStepsReachTheNewtonMinimumWithFewerFactorisations) {
  StaticSolverParams p;
  p.shift_indefinite = true;
  p.max_iterations = 100;
  Cantilever newton(make_corotational_shell(), 4.0, 16, 1);
  StaticSolverParams only_newton = p;
  only_newton.quasi_newton_steps = 0;
  const StaticResult a = solve_static(newton.sys, newton.state, only_newton);
  ASSERT_TRUE(a.converged) << a.message;
  EXPECT_EQ(a.quasi_newton_iterations, 0);

  Cantilever quasi(make_corotational_shell(), 4.0, 16, 1);
  SolverWorkspace ws;
  const StaticResult b = solve_static(quasi.sys, quasi.state, p, &ws);
  ASSERT_TRUE(b.converged) << b.message;
  EXPECT_GT(b.quasi_newton_iterations, 0);
  EXPECT_LT(b.iterations, a.iterations);  // measured: 30 (and 108 quasi-Newton) against 52
  for (std::size_t k = 1; k < b.history.size(); ++k)
    EXPECT_LE(b.history[k].potential, b.history[k - 1].potential + 1e-12) << "step " << k;
  // Both to the relative force tolerance 1e-8 of a 13 mm deflection.
  EXPECT_LT((quasi.tip_displacement() - newton.tip_displacement()).norm(), 1e-6);

  // 10 % more load from there in one load step: from the tangent at the start.
  StaticSolverParams more = p;
  more.lambda_start = 1.0;
  more.lambda_end = 1.1;
  StaticSolverParams more_newton = more;
  more_newton.quasi_newton_steps = 0;
  Cantilever reference(make_corotational_shell(), 4.0, 16, 1);
  reference.state = quasi.state;
  const StaticResult c = solve_static(reference.sys, reference.state, more_newton);
  ASSERT_TRUE(c.converged) << c.message;
  const StaticResult d = solve_static(quasi.sys, quasi.state, more, &ws);
  ASSERT_TRUE(d.converged) << d.message;
  EXPECT_LT(d.iterations, c.iterations);  // measured: 2 (+ 15) against 8
  EXPECT_LT((quasi.tip_displacement() - reference.tip_displacement()).norm(), 1e-6);

  // The same 10 % at a fixed load factor (lambda_start = lambda_end = 1.1 from the equilibrium
  // at 1, as a relaxation increment starts where its rest shape has just moved): cold, the
  // first step needs a tangent; primed with the tangent at the old equilibrium
  // (factorize_for_quasi_newton), it does not.
  StaticSolverParams fixed = p;
  fixed.lambda_start = fixed.lambda_end = 1.1;
  Cantilever cold(make_corotational_shell(), 4.0, 16, 1);
  cold.state = newton.state;
  SolverWorkspace cold_ws;
  const StaticResult e = solve_static(cold.sys, cold.state, fixed, &cold_ws);
  ASSERT_TRUE(e.converged) << e.message;
  Cantilever primed(make_corotational_shell(), 4.0, 16, 1);
  primed.state = newton.state;
  SolverWorkspace primed_ws;
  ASSERT_TRUE(factorize_for_quasi_newton(primed.sys, primed.state, 1.0, primed_ws));
  const StaticResult f = solve_static(primed.sys, primed.state, fixed, &primed_ws);
  ASSERT_TRUE(f.converged) << f.message;
  EXPECT_LT(f.iterations, e.iterations);  // measured: 1 (+ 23) against 3 (+ 13)
  EXPECT_LT((primed.tip_displacement() - cold.tip_displacement()).norm(), 1e-6);
  // Anything else factorising in the workspace's solver invalidates the start: then the path
  // is the cold one, step for step.
  Cantilever stale(make_corotational_shell(), 4.0, 16, 1);
  stale.state = newton.state;
  SolverWorkspace stale_ws;
  ASSERT_TRUE(factorize_for_quasi_newton(stale.sys, stale.state, 1.0, stale_ws));
  LinearSolver& solver = stale_ws.solver(LinearSolverKind::Cholmod, {});
  Eigen::SparseMatrix<double> I(3, 3);
  I.setIdentity();
  ASSERT_TRUE(solver.factorize(I));
  EXPECT_FALSE(stale_ws.holds_reusable_factor(3));
  const StaticResult g = solve_static(stale.sys, stale.state, fixed, &stale_ws);
  ASSERT_TRUE(g.converged) << g.message;
  EXPECT_EQ(g.iterations, e.iterations);
  EXPECT_EQ(g.quasi_newton_iterations, e.quasi_newton_iterations);
  EXPECT_EQ(stale.state.x, cold.state.x);
}

TEST(StaticSolver, RejectsBadParameters) {
  {
    Cantilever c(make_corotational_shell(), 1.0, 4, 1);
    StaticSolverParams p;
    p.min_area_ratio = 1.0;
    EXPECT_THROW(solve_static(c.sys, c.state, p), InvalidArgument);
  }
  Cantilever c(make_corotational_shell(), 1.0);
  StaticSolverParams p;
  p.load_steps = 0;
  EXPECT_THROW(solve_static(c.sys, c.state, p), InvalidArgument);
  p = {};
  p.tolerance = 0.0;
  EXPECT_THROW(solve_static(c.sys, c.state, p), InvalidArgument);
  p = {};
  p.quasi_newton_steps = -1;
  EXPECT_THROW(solve_static(c.sys, c.state, p), InvalidArgument);
}

// The quasi-Newton steps solve in single precision by default (single_precision_solves): the
// same minimum as with exact solves, to the force tolerance.
TEST(StaticSolver, SinglePrecisionQuasiNewtonStepsReachTheSameMinimum) {
  StaticSolverParams p;
  p.shift_indefinite = true;
  p.max_iterations = 100;
  StaticSolverParams exact = p;
  exact.single_precision_solves = false;
  Cantilever a(make_corotational_shell(), 4.0, 16, 1), b(make_corotational_shell(), 4.0, 16, 1);
  const StaticResult ra = solve_static(a.sys, a.state, p);
  const StaticResult rb = solve_static(b.sys, b.state, exact);
  ASSERT_TRUE(ra.converged) << ra.message;
  ASSERT_TRUE(rb.converged) << rb.message;
  EXPECT_GT(ra.quasi_newton_iterations, 0);
  EXPECT_GT(b.tip_displacement().norm(), 5.0);  // Sze: -u 3.29, w 6.70
  EXPECT_LT((a.tip_displacement() - b.tip_displacement()).norm(), 1e-6);
  EXPECT_NE(a.state.x, b.state.x);  // the single-precision path was taken
}
