// Tests of Model 1, the corotational ANDES-OPT + DKT shell: derivatives against finite
// differences, invariance under rigid motions, patch tests, beam benchmarks and Newton
// convergence. Tolerances are stated with each assertion.
#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "corotational_test_support.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

using test::FlatArrays;
using test::ProblemSetup;

constexpr double kPi = std::numbers::pi;

std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3e", v);
  return buf;
}

ShellMaterial material(double E, double nu, double t) {
  ShellMaterial m;
  m.youngs_modulus = E;
  m.poisson_ratio = nu;
  m.thickness = t;
  return m;
}

/// A curved 3 x 3-cell cylinder panel (cells about 1 mm) with random rest triads, and a state
/// perturbed from it by random translations (up to 10 % of a cell) and random rotations (up
/// to 0.5 rad).
struct PerturbedPanel {
  FlatArrays mesh = test::cylinder_panel(5.0, 0.6, 3.0, 3, 3);
  ShellState rest_state;
  std::unique_ptr<ProblemSetup> setup;
  ShellState state;

  explicit PerturbedPanel(unsigned seed, const ShellMaterial& m = material(2.0, 0.3, 0.3)) {
    std::mt19937 rng(seed);
    rest_state = test::identity_state(mesh.x);
    for (Quat& q : rest_state.D) q = test::random_rotation(rng, kPi);
    setup = std::make_unique<ProblemSetup>(mesh, rest_state, m);
    state = rest_state;
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    for (Vec3& x : state.x) x += Vec3(u(rng), u(rng), u(rng));
    for (Quat& q : state.D) q = test::random_rotation(rng, 0.5) * q;
  }
};

TEST(CorotationalShell, GradientMatchesCentralDifferencesOfEnergy) {
  const auto model = make_corotational_shell();
  for (unsigned seed : {1u, 2u, 3u}) {
    PerturbedPanel panel(seed);
    const ShellProblem p = panel.setup->problem();
    Eigen::VectorXd g;
    model->energy_gradient(p, panel.state, g);
    ASSERT_EQ(g.size(), 16 * 6);
    // Step 1e-6 (mm for translations, rad for spins): truncation ~h^2 and round-off
    // ~1e-16/h are both far below the tolerance.
    const double h = 1e-6;
    Eigen::VectorXd fd(g.size());
    for (Eigen::Index k = 0; k < g.size(); ++k)
      fd(k) = (model->energy(p, test::displaced(panel.state, k, h, 6)) -
               model->energy(p, test::displaced(panel.state, k, -h, 6))) /
              (2.0 * h);
    const double err = (fd - g).norm() / g.norm();
    RecordProperty("gradient_fd_relative_error_seed" + std::to_string(seed), sci(err));
    EXPECT_LT(err, 1e-7) << "seed " << seed;
  }
}

TEST(CorotationalShell, TangentMatchesCentralDifferencesOfGradient) {
  const auto model = make_corotational_shell();
  for (unsigned seed : {1u, 2u, 3u}) {
    PerturbedPanel panel(seed);
    const ShellProblem p = panel.setup->problem();
    Eigen::VectorXd g;
    Triplets t;
    model->energy_gradient_hessian(p, panel.state, g, t, /*symmetric=*/false);
    const Eigen::MatrixXd K = test::assemble(t, g.size());
    const double h = 1e-6;
    Eigen::MatrixXd fd(g.size(), g.size());
    for (Eigen::Index k = 0; k < g.size(); ++k) {
      Eigen::VectorXd gp, gm;
      model->energy_gradient(p, test::displaced(panel.state, k, h, 6), gp);
      model->energy_gradient(p, test::displaced(panel.state, k, -h, 6), gm);
      fd.col(k) = (gp - gm) / (2.0 * h);
    }
    const double err = (fd - K).norm() / K.norm();
    RecordProperty("tangent_fd_relative_error_seed" + std::to_string(seed), sci(err));
    EXPECT_LT(err, 1e-7) << "seed " << seed;
    // Away from equilibrium the consistent tangent is genuinely nonsymmetric.
    EXPECT_GT((K - K.transpose()).norm(), 1e-6 * K.norm());
  }
}

TEST(CorotationalShell, SymmetricTangentIsTheSymmetricPart) {
  const auto model = make_corotational_shell();
  PerturbedPanel panel(4);
  const ShellProblem p = panel.setup->problem();
  Eigen::VectorXd g1, g2;
  Triplets t1, t2;
  const double e1 = model->energy_gradient_hessian(p, panel.state, g1, t1, false);
  const double e2 = model->energy_gradient_hessian(p, panel.state, g2, t2, true);
  const Eigen::MatrixXd K = test::assemble(t1, g1.size());
  const Eigen::MatrixXd Ks = test::assemble(t2, g2.size());
  EXPECT_EQ(e1, e2);
  EXPECT_EQ((g1 - g2).norm(), 0.0);
  // Round-off only.
  EXPECT_LT((Ks - 0.5 * (K + K.transpose())).norm(), 1e-13 * K.norm());
  EXPECT_LT((Ks - Ks.transpose()).norm(), 1e-13 * K.norm());
  // The nonsymmetry of the consistent tangent comes only from the non-commuting spin
  // increments: exp(w) exp(w') = exp(w + w' + 1/2 w x w' + ...) makes the antisymmetric part
  // -1/2 [g_w]x on each node's spin-spin block and zero elsewhere.
  Eigen::MatrixXd skew_part = 0.5 * (K - K.transpose());
  for (Eigen::Index i = 0; i < g1.size() / 6; ++i) {
    const Vec3 gw = g1.segment<3>(6 * i + 3);
    Eigen::Matrix3d S;
    S << 0.0, -gw.z(), gw.y(), gw.z(), 0.0, -gw.x(), -gw.y(), gw.x(), 0.0;
    skew_part.block<3, 3>(6 * i + 3, 6 * i + 3) += 0.5 * S;
  }
  EXPECT_LT(skew_part.norm(), 1e-13 * K.norm());
  // The symmetric part is the Hessian of the energy: second central differences of the
  // energy along random directions (step 1e-4: error ~h^2 relative).
  std::mt19937 rng(5);
  std::normal_distribution<double> n01;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd v(g1.size());
    for (Eigen::Index k = 0; k < v.size(); ++k) v(k) = n01(rng);
    const double h = 1e-4;
    ShellState sp = panel.state, sm = panel.state;
    apply_increment(sp, h * v, 6);
    apply_increment(sm, -h * v, 6);
    const double e0 = model->energy(p, panel.state);
    const double fd = (model->energy(p, sp) - 2.0 * e0 + model->energy(p, sm)) / (h * h);
    EXPECT_NEAR(fd, v.dot(Ks * v), 1e-5 * std::abs(v.dot(Ks * v)));
  }
}

TEST(CorotationalShell, RigidBodyMotionGivesZeroEnergyAndForce) {
  const auto model = make_corotational_shell();
  PerturbedPanel panel(6);
  const ShellProblem p = panel.setup->problem();
  const Quat R(Eigen::AngleAxisd(2.3, Vec3(1.0, -2.0, 0.5).normalized()));
  const Vec3 c(100.0, -40.0, 250.0);
  // From the (curved, non-identity-triad) rest state.
  ShellState moved = panel.rest_state;
  for (Vec3& x : moved.x) x = R * x + c;
  for (Quat& q : moved.D) q = R * q;
  Eigen::VectorXd g;
  const double E = model->energy_gradient(p, moved, g);
  // Scales: force E t h = 2 * 0.3 * 1 N, energy E t h^2 = 0.6 N mm (h = 1 mm cells).
  // Positions of size 250 carry round-off ~6e-14, so the bounds are ~1e-10 of the scales.
  EXPECT_LT(std::abs(E), 1e-20);
  EXPECT_LT(g.lpNorm<Eigen::Infinity>(), 1e-10 * 0.6);
  // From a deformed state: the energy is invariant and the gradient rotates with the body.
  Eigen::VectorXd g0, g1;
  const double E0 = model->energy_gradient(p, panel.state, g0);
  ShellState deformed = panel.state;
  for (Vec3& x : deformed.x) x = R * x + c;
  for (Quat& q : deformed.D) q = R * q;
  const double E1 = model->energy_gradient(p, deformed, g1);
  EXPECT_NEAR(E1, E0, 1e-11 * E0);
  Eigen::VectorXd g0r = g0;
  for (Eigen::Index k = 0; k < g0.size(); k += 3) g0r.segment<3>(k) = R * g0.segment<3>(k);
  EXPECT_LT((g1 - g0r).norm(), 1e-10 * g0.norm());
}

/// Energy of the perturbed panel of `seed` with thickness t and all lengths scaled by lambda.
double scaled_panel_energy(unsigned seed, double t, double lambda) {
  const PerturbedPanel panel(seed, material(2.0, 0.3, t));
  FlatArrays mesh = panel.mesh;
  ShellState rest = panel.rest_state, state = panel.state;
  for (Vec3& x : mesh.x) x *= lambda;
  for (Vec3& x : rest.x) x *= lambda;
  for (Vec3& x : state.x) x *= lambda;
  const ProblemSetup setup(mesh, rest, material(2.0, 0.3, t));
  return make_corotational_shell()->energy(setup.problem(), state);
}

TEST(CorotationalShell, EnergyScalesWithThicknessAndMeshSize) {
  // The kinematics do not depend on t and K_e = t K_membrane + t^3 K_bending, so
  // E(t) = a t + b t^3 exactly. Scaling rest and current geometry by lambda keeps strains and
  // rotations and divides curvatures by lambda: E(lambda) = c lambda^2 + d (membrane energy
  // grows with the area, bending energy is size independent). Fit on two points, predict a
  // third; round-off only.
  for (unsigned seed : {1u, 2u}) {
    const double e1 = scaled_panel_energy(seed, 0.1, 1.0), e2 = scaled_panel_energy(seed, 0.2, 1.0);
    const double b = (e2 - 2.0 * e1) / (0.008 - 0.002);
    const double a = (e1 - b * 0.001) / 0.1;
    ASSERT_GT(a, 0.0);
    ASSERT_GT(b, 0.0);
    const double e4 = scaled_panel_energy(seed, 0.4, 1.0);
    EXPECT_NEAR(e4, a * 0.4 + b * 0.064, 1e-11 * e4);
    const double l1 = scaled_panel_energy(seed, 0.3, 1.0), l2 = scaled_panel_energy(seed, 0.3, 2.0);
    const double c = (l2 - l1) / 3.0, d = l1 - c;
    const double l3 = scaled_panel_energy(seed, 0.3, 3.0);
    EXPECT_NEAR(l3, 9.0 * c + d, 1e-11 * l3);
  }
}

TEST(CorotationalShell, ParallelAssemblyIsBitwiseRepeatable) {
  // 1920 elements: above the OpenMP threshold.
  const auto model = make_corotational_shell();
  const FlatArrays tube = test::tube(3.0, 10.0, 48, 20);
  std::mt19937 rng(21);
  ShellState s = test::identity_state(tube.x);
  const ProblemSetup setup(tube, s, ShellMaterial{});
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  for (Vec3& x : s.x) x += Vec3(u(rng), u(rng), u(rng));
  for (Quat& q : s.D) q = test::random_rotation(rng, 0.2) * q;
  Eigen::VectorXd g1, g2;
  Triplets t1, t2;
  const double e1 = model->energy_gradient_hessian(setup.problem(), s, g1, t1, false);
  const double e2 = model->energy_gradient_hessian(setup.problem(), s, g2, t2, false);
  EXPECT_EQ(e1, e2);
  EXPECT_EQ(e1, model->energy(setup.problem(), s));
  EXPECT_TRUE((g1.array() == g2.array()).all());
  ASSERT_EQ(t1.size(), tube.faces.size() * 18 * 18);
  ASSERT_EQ(t1.size(), t2.size());
  bool same = true;
  for (std::size_t i = 0; i < t1.size(); ++i)
    same = same && t1[i].row() == t2[i].row() && t1[i].col() == t2[i].col() &&
           t1[i].value() == t2[i].value();
  EXPECT_TRUE(same);
}

// The model keeps each element's rest-dependent stiffness between calls (a memo keyed by the
// element's rest geometry and material): a model reused across changing rest states, materials
// and meshes must give bitwise the results of a fresh model, and a rest triangle made
// degenerate after a good one must still be rejected.
TEST(CorotationalShell, ReusedModelFollowsRestMaterialAndMeshChangesBitwise) {
  const auto reused = make_corotational_shell();
  const auto check = [&](const ShellProblem& p, const ShellState& s, const std::string& what) {
    const auto fresh = make_corotational_shell();
    Eigen::VectorXd g1, g2;
    Triplets t1, t2;
    const double e1 = reused->energy_gradient_hessian(p, s, g1, t1, true);
    const double e2 = fresh->energy_gradient_hessian(p, s, g2, t2, true);
    EXPECT_EQ(e1, e2) << what;
    ASSERT_EQ(g1.size(), g2.size()) << what;
    EXPECT_TRUE((g1.array() == g2.array()).all()) << what;
    ASSERT_EQ(t1.size(), t2.size()) << what;
    bool same = true;
    for (std::size_t i = 0; i < t1.size(); ++i) same = same && t1[i].value() == t2[i].value();
    EXPECT_TRUE(same) << what;
    EXPECT_EQ(reused->energy(p, s), fresh->energy(p, s)) << what;
  };
  PerturbedPanel panel(5);
  check(panel.setup->problem(), panel.state, "first call");
  check(panel.setup->problem(), panel.state, "second call");
  // Relaxation-like change of a few elements' rest geometry and triads.
  panel.setup->rest.elements[3].X[1] += Vec3(0.05, -0.02, 0.01);
  panel.setup->rest.elements[7].Q[2] = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY())) *
                                       panel.setup->rest.elements[7].Q[2];
  check(panel.setup->problem(), panel.state, "rest changed");
  panel.setup->materials[0].thickness = 0.2;
  check(panel.setup->problem(), panel.state, "thickness changed");
  panel.setup->materials[0].drilling_factor = 0.5;
  check(panel.setup->problem(), panel.state, "drilling factor changed");
  // Another mesh (more elements) through the same model, then the panel again.
  const FlatArrays tube = test::tube(3.0, 10.0, 12, 4);
  const ProblemSetup tube_setup(tube, test::identity_state(tube.x), material(1.0, 0.45, 0.5));
  ShellState tube_state = test::identity_state(tube.x);
  tube_state.x[5] += Vec3(0.1, 0.0, -0.05);
  check(tube_setup.problem(), tube_state, "other mesh");
  check(panel.setup->problem(), panel.state, "panel again");
  // A degenerate rest triangle after a good one is still rejected.
  auto& e = panel.setup->rest.elements[4];
  e.X[2] = e.X[0];
  Eigen::VectorXd g;
  EXPECT_THROW(reused->energy_gradient(panel.setup->problem(), panel.state, g), InvalidArgument);
}

/// Plane-stress energy density 1/2 eps : C : eps per unit thickness (eps a tensor).
double membrane_energy_density(const Eigen::Matrix2d& eps, const ShellMaterial& m) {
  const double E = m.youngs_modulus, nu = m.poisson_ratio;
  const Eigen::Vector3d e(eps(0, 0), eps(1, 1), 2.0 * eps(0, 1));
  Eigen::Matrix3d C;
  C << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, 0.5 * (1.0 - nu);
  return 0.5 * e.dot((E / (1.0 - nu * nu)) * C * e);
}

TEST(CorotationalShell, ConstantMembraneStrainPatchTest) {
  const auto model = make_corotational_shell();
  const FlatArrays mesh = test::irregular_patch(4.0);
  const ShellMaterial m = material(3.0, 0.3, 0.1);
  ProblemSetup setup(mesh, test::identity_state(mesh.x), m);
  const ShellProblem p = setup.problem();
  Eigen::Matrix2d eps;
  eps << 2e-7, 0.5e-7, 0.5e-7, -1e-7;
  const double area = 16.0;
  const double expected = membrane_energy_density(eps, m) * m.thickness * area;
  // Also under a large superposed rigid rotation (the triads rotate with the body).
  const Quat R(Eigen::AngleAxisd(1.1, Vec3(0.3, 1.0, -0.4).normalized()));
  for (const Quat& rot : {Quat::Identity(), R}) {
    ShellState s = test::identity_state(mesh.x);
    for (Vec3& x : s.x) {
      const Eigen::Vector2d u = eps * x.head<2>();
      x = rot * (x + Vec3(u.x(), u.y(), 0.0));
    }
    for (Quat& q : s.D) q = rot;
    Eigen::VectorXd g;
    const double E = model->energy_gradient(p, s, g);
    // Exact for the linear element; the corotational geometry deviates by O(|eps|) ~ 1e-7.
    EXPECT_NEAR(E, expected, 1e-6 * expected);
    RecordProperty(rot.w() == 1.0 ? "membrane_patch_error" : "membrane_patch_rotated_error",
                   sci(std::abs(E - expected) / expected));
    // Uniform stress: zero resultant at the interior nodes (relative to boundary forces).
    double interior = 0.0, boundary = 0.0;
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) {
        const double f = g.segment<6>(6 * (5 * j + i)).norm();
        if (i > 0 && i < 4 && j > 0 && j < 4)
          interior = std::max(interior, f);
        else
          boundary = std::max(boundary, f);
      }
    EXPECT_LT(interior, 1e-5 * boundary);
  }
}

TEST(CorotationalShell, ConstantCurvaturePatchTest) {
  const auto model = make_corotational_shell();
  const FlatArrays mesh = test::irregular_patch(4.0);
  const ShellMaterial m = material(3.0, 0.3, 0.1);
  ProblemSetup setup(mesh, test::identity_state(mesh.x), m);
  const ShellProblem p = setup.problem();
  const double D = m.youngs_modulus * std::pow(m.thickness, 3) / (12.0 * (1.0 - 0.09));
  struct Case {
    double a, b, c;  // w = 1/2 (a x^2 + 2 b x y + c y^2)
  };
  for (const Case k : {Case{1e-6, 0.0, 0.0}, Case{0.7e-6, -0.4e-6, -0.3e-6}}) {
    ShellState s = test::identity_state(mesh.x);
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const double x = mesh.x[i].x(), y = mesh.x[i].y();
      s.x[i].z() = 0.5 * (k.a * x * x + 2.0 * k.b * x * y + k.c * y * y);
      // Kirchhoff rotations: theta_x = w_y, theta_y = -w_x.
      s.D[i] = test::rotation(Vec3(k.b * x + k.c * y, -(k.a * x + k.b * y), 0.0));
    }
    // Energy 1/2 kappa^T D_b kappa A with kappa = (w_xx, w_yy, 2 w_xy).
    const double nu = m.poisson_ratio;
    const double expected =
        0.5 * D * (k.a * k.a + k.c * k.c + 2.0 * nu * k.a * k.c + 0.5 * (1.0 - nu) * 4.0 * k.b * k.b) *
        16.0;
    // Geometric nonlinearity and membrane coupling are O((kappa L)^2 (L/t)^2) ~ 1e-8 here.
    const double E = model->energy(p, s);
    EXPECT_NEAR(E, expected, 1e-6 * expected);
    RecordProperty(k.b == 0.0 ? "bending_patch_error" : "bending_patch_twist_error",
                   sci(std::abs(E - expected) / expected));
    const ElementMeasures ms = model->measures(p, s);
    const double kmax = std::max(std::abs(0.5 * (k.a + k.c) + std::hypot(0.5 * (k.a - k.c), k.b)),
                                 std::abs(0.5 * (k.a + k.c) - std::hypot(0.5 * (k.a - k.c), k.b)));
    for (const double kf : ms.bending_curvature) EXPECT_NEAR(kf, kmax, 1e-6 * kmax);
  }
}

/// Cantilever strip along x clamped at x = 0 (all 6 DOFs of the root nodes).
struct Cantilever {
  double length, width;
  int nx, ny;
  FlatArrays mesh;
  ProblemSetup setup;
  std::vector<bool> free;

  Cantilever(double L, double W, int nx_, int ny_, const ShellMaterial& m)
      : length(L), width(W), nx(nx_), ny(ny_), mesh(test::strip(L, W, nx_, ny_)),
        setup(mesh, test::identity_state(mesh.x), m), free(mesh.x.size() * 6, true) {
    for (int j = 0; j <= ny; ++j)
      for (int d = 0; d < 6; ++d) free[6 * node(0, j) + d] = false;
  }
  [[nodiscard]] int node(int i, int j) const { return j * (nx + 1) + i; }
  /// Consistent nodal loads of a uniform line load along the tip edge totalling `total` on
  /// DOF `dof` (trapezoidal weights).
  [[nodiscard]] Eigen::VectorXd tip_load(int dof, double total) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(free.size()));
    for (int j = 0; j <= ny; ++j)
      f(6 * node(nx, j) + dof) = total / ny * ((j == 0 || j == ny) ? 0.5 : 1.0);
    return f;
  }
  /// Mean of coordinate `c` of the displacement of the tip nodes.
  [[nodiscard]] double tip(const ShellState& s, int c) const {
    double sum = 0.0;
    for (int j = 0; j <= ny; ++j) sum += s.x[node(nx, j)](c) - mesh.x[node(nx, j)](c);
    return sum / (ny + 1);
  }
  /// Linear solution u = K^{-1} f at the rest state (symmetric tangent, clamped DOFs removed).
  [[nodiscard]] Eigen::VectorXd linear_solution(const ShellModel& model,
                                                const Eigen::VectorXd& f) const {
    Eigen::VectorXd g;
    Triplets t;
    model.energy_gradient_hessian(setup.problem(), test::identity_state(mesh.x), g, t, true);
    std::vector<Eigen::Index> reduced(free.size(), -1);
    Eigen::Index nf = 0;
    for (std::size_t k = 0; k < free.size(); ++k)
      if (free[k]) reduced[k] = nf++;
    Triplets tr;
    for (const auto& e : t)
      if (free[e.row()] && free[e.col()]) tr.emplace_back(reduced[e.row()], reduced[e.col()], e.value());
    Eigen::VectorXd fr(nf);
    for (std::size_t k = 0; k < free.size(); ++k)
      if (free[k]) fr(reduced[k]) = f(static_cast<Eigen::Index>(k));
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(test::assemble(tr, nf));
    EXPECT_EQ(ldlt.info(), Eigen::Success);
    const Eigen::VectorXd ur = ldlt.solve(fr);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(f.size());
    for (std::size_t k = 0; k < free.size(); ++k)
      if (free[k]) u(static_cast<Eigen::Index>(k)) = ur(reduced[k]);
    return u;
  }
};

TEST(CorotationalShell, CantileverTipShearMatchesBeamTheory) {
  // nu = 0: the strip bends like a beam, w = P x^2 (3L - x) / (6 E I), I = W t^3 / 12.
  const auto model = make_corotational_shell();
  const ShellMaterial m = material(1.0, 0.0, 0.2);
  Cantilever c(20.0, 2.0, 20, 2, m);
  const double P = 1e-6;
  const Eigen::VectorXd u = c.linear_solution(*model, c.tip_load(2, P));
  double tip = 0.0;
  for (int j = 0; j <= c.ny; ++j) tip += u(6 * c.node(c.nx, j) + 2) / (c.ny + 1);
  const double I = c.width * std::pow(m.thickness, 3) / 12.0;
  const double exact = P * std::pow(c.length, 3) / (3.0 * m.youngs_modulus * I);
  const double err = std::abs(tip - exact) / exact;
  RecordProperty("cantilever_20x2_relative_error", sci(err));
  EXPECT_LT(err, 0.01) << "tip " << tip << " exact " << exact;
}

TEST(CorotationalShell, InPlaneCantileverMatchesTimoshenkoBeamForAnyDrillingFactor) {
  // ANDES-OPT is near bending-exact in plane with two elements across the depth, where a
  // constant-strain triangle would be far too stiff. Timoshenko beam with shear factor 5/6,
  // nu = 0 (G = E/2): v = P L^3 / (3 E I) + P L / (5/6 G W t), I = t W^3 / 12.
  const auto model = make_corotational_shell();
  for (const double drilling : {1e-3, 0.1, 1.0}) {
    ShellMaterial m = material(1.0, 0.0, 0.2);
    m.drilling_factor = drilling;
    Cantilever c(20.0, 2.0, 20, 2, m);
    const double P = 1e-6;
    const Eigen::VectorXd u = c.linear_solution(*model, c.tip_load(1, P));
    double tip = 0.0;
    for (int j = 0; j <= c.ny; ++j) tip += u(6 * c.node(c.nx, j) + 1) / (c.ny + 1);
    const double I = m.thickness * std::pow(c.width, 3) / 12.0;
    const double exact = P * std::pow(c.length, 3) / (3.0 * I) +
                         P * c.length / (5.0 / 6.0 * 0.5 * c.width * m.thickness);
    const double err = std::abs(tip - exact) / exact;
    RecordProperty("inplane_cantilever_error_drilling_" + std::to_string(drilling),
                   sci(err));
    // Clamping every root node (no warping) and the coarse depth cost a few percent.
    EXPECT_LT(err, 0.03) << "drilling factor " << drilling << ": tip " << tip << " exact " << exact;
  }
}

/// Round-off floor of residuals: local coordinates carry errors ~1e-16 of the coordinates,
/// which the membrane stiffness E t turns into forces ~1e-16 E t L; a bound 100x above it.
double residual_floor(const ShellMaterial& m, double length) {
  return 1e-14 * m.youngs_modulus * m.thickness * length;
}

TEST(CorotationalShell, SmallLoadNewtonMatchesLinearSolution) {
  const auto model = make_corotational_shell();
  const ShellMaterial m = material(1.0, 0.3, 0.2);
  Cantilever c(20.0, 2.0, 10, 2, m);
  // Tip deflection about 1e-4 L: nonlinear effects are O(1e-4) relative.
  const double I = c.width * std::pow(m.thickness, 3) / 12.0;
  const double P = 1e-4 * c.length * 3.0 * I / std::pow(c.length, 3);
  const Eigen::VectorXd f = c.tip_load(2, P);
  const Eigen::VectorXd u_lin = c.linear_solution(*model, f);
  // One Newton step from rest: the tangent at rest is the linear stiffness.
  ShellState s = test::identity_state(c.mesh.x);
  const auto h1 = test::newton(*model, c.setup.problem(), s, f, c.free, 0.0, 1);
  ASSERT_EQ(h1.size(), 2u);
  for (std::size_t i = 0; i < s.x.size(); ++i)
    EXPECT_NEAR((s.x[i] - c.mesh.x[i] - u_lin.segment<3>(6 * i)).norm(), 0.0,
                1e-9 * u_lin.norm());
  // Converged nonlinear solution.
  const double tol = 1e-10 * f.norm() + residual_floor(m, c.length);
  const auto h = test::newton(*model, c.setup.problem(), s, f, c.free, tol, 20);
  ASSERT_LT(h.back(), tol);
  double tip_lin = 0.0;
  for (int j = 0; j <= c.ny; ++j) tip_lin += u_lin(6 * c.node(c.nx, j) + 2) / (c.ny + 1);
  EXPECT_NEAR(c.tip(s, 2), tip_lin, 1e-3 * std::abs(tip_lin));
}

TEST(CorotationalShell, EndMomentRollsStripIntoHalfCircleWithQuadraticConvergence) {
  // M = pi E I / L bends the strip into a half circle of radius L/pi (nu = 0): the tip
  // reaches x = 0, z = 2 L / pi. Twenty load steps of 9 degrees of tip rotation each: the
  // tangent predictor moves the nodes along straight lines, whose membrane stretch (the
  // membrane is (L/t)^2 = 1e4 times stiffer than bending) limits the step size.
  const auto model = make_corotational_shell();
  const ShellMaterial m = material(1.0, 0.0, 0.2);
  Cantilever c(20.0, 2.0, 20, 1, m);
  const double I = c.width * std::pow(m.thickness, 3) / 12.0;
  const double M = kPi * m.youngs_modulus * I / c.length;
  // Moment about -y curls the strip towards +z.
  const Eigen::VectorXd f_total = -c.tip_load(4, M);
  const double fn = f_total.norm();
  const double floor = residual_floor(m, c.length);
  ShellState s = test::identity_state(c.mesh.x);
  const int steps = 20;
  int checked = 0;
  for (int k = 1; k <= steps; ++k) {
    const Eigen::VectorXd f = f_total * (static_cast<double>(k) / steps);
    const double tol = 1e-10 * fn + floor;
    const auto r = test::newton(*model, c.setup.problem(), s, f, c.free, tol, 25);
    ASSERT_LT(r.back(), tol) << "load step " << k;
    std::string seq;
    for (const double v : r) seq += sci(v / fn) + " ";
    RecordProperty("newton_relative_residuals_step_" + std::to_string(k), seq);
    // Quadratic convergence near the solution: r_{k+1} < 10 r_k^1.8 (residuals relative to
    // the total load) once r_k < 1e-2, for r_{k+1} above ten times the round-off floor.
    for (std::size_t i = 0; i + 1 < r.size(); ++i) {
      const double ri = r[i] / fn, rn = r[i + 1] / fn;
      if (ri < 1e-2 && r[i + 1] > 10.0 * floor) {
        EXPECT_LT(rn, 10.0 * std::pow(ri, 1.8)) << "load step " << k << ", iteration " << i;
        ++checked;
      }
    }
  }
  EXPECT_GE(checked, steps);
  const double rho = c.length / kPi;
  // Mesh error of 20 elements along the strip: well below 1 % of the radius.
  EXPECT_NEAR(c.tip(s, 0) + c.length, 0.0, 0.01 * rho);
  EXPECT_NEAR(c.tip(s, 2), 2.0 * rho, 0.01 * rho);
}

TEST(CorotationalShell, MeasuresOfUniformStretch) {
  const auto model = make_corotational_shell();
  const FlatArrays mesh = test::irregular_patch(4.0);
  const ShellMaterial m = material(3.0, 0.3, 0.1);
  ProblemSetup setup(mesh, test::identity_state(mesh.x), m);
  const double lambda = 1.2;  // large stretch along x: Green-Lagrange (lambda^2 - 1)/2
  ShellState s = test::identity_state(mesh.x);
  for (Vec3& x : s.x) x.x() *= lambda;
  const ElementMeasures ms = model->measures(setup.problem(), s);
  ASSERT_EQ(ms.membrane_strain.size(), mesh.faces.size());
  const double energy = model->energy(setup.problem(), s);
  double energy_from_density = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    EXPECT_NEAR(ms.membrane_strain[f], 0.5 * (lambda * lambda - 1.0), 1e-12);
    EXPECT_NEAR(ms.bending_curvature[f], 0.0, 1e-12);
    const auto& fc = mesh.faces[f];
    const double area = 0.5 * (mesh.x[fc[1]] - mesh.x[fc[0]]).cross(mesh.x[fc[2]] - mesh.x[fc[0]]).norm();
    energy_from_density += ms.energy_density[f] * area;
  }
  EXPECT_NEAR(energy_from_density, energy, 1e-12 * energy);
}

TEST(CorotationalShell, RejectsInvalidInput) {
  const auto model = make_corotational_shell();
  const FlatArrays mesh = test::strip(2.0, 1.0, 2, 1);
  ShellState s = test::identity_state(mesh.x);
  ProblemSetup setup(mesh, s, material(1.0, 0.3, 0.1));
  setup.materials[0].poisson_ratio = 0.5;
  EXPECT_THROW((void)model->energy(setup.problem(), s), InvalidArgument);
  setup.materials[0].poisson_ratio = 0.3;
  setup.rest.elements[1].X[2] = setup.rest.elements[1].X[0];  // degenerate rest triangle
  try {
    (void)model->energy(setup.problem(), s);
    ADD_FAILURE() << "degenerate rest triangle accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("face 1"), std::string::npos) << e.what();
  }
  s.x.pop_back();
  EXPECT_THROW((void)model->energy(setup.problem(), s), InvalidArgument);
}

TEST(ShellMaterial, ValidateNamesFieldAndValue) {
  EXPECT_NO_THROW(validate(ShellMaterial{}));
  auto message = [](ShellMaterial m) -> std::string {
    try {
      validate(m);
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "";
  };
  ShellMaterial m;
  m.youngs_modulus = -2.0;
  EXPECT_NE(message(m).find("youngs_modulus = -2"), std::string::npos) << message(m);
  m = {};
  m.poisson_ratio = 0.5;
  EXPECT_NE(message(m).find("poisson_ratio = 0.5"), std::string::npos) << message(m);
  m = {};
  m.thickness = 0.0;
  EXPECT_NE(message(m).find("thickness = 0"), std::string::npos) << message(m);
  m = {};
  m.density = std::nan("");
  EXPECT_NE(message(m).find("density"), std::string::npos) << message(m);
  m = {};
  m.drilling_factor = 0.0;
  EXPECT_NE(message(m).find("drilling_factor = 0"), std::string::npos) << message(m);
}

// A Poisson ratio a hair below 0.5 is valid but warned about: from kNearlyIncompressible on,
// ANDES-OPT's beta0 = (1 - 4 nu^2) / 2 is below its floor 0.01 (issue 27).
TEST(ShellMaterial, ANearlyIncompressibleWallIsWarnedAbout) {
  ShellMaterial m;
  EXPECT_EQ(material_warning(m), "");
  m.poisson_ratio = 0.49;
  EXPECT_EQ(material_warning(m), "");
  EXPECT_GT(0.5 * (1.0 - 4.0 * 0.49 * 0.49), 0.01);
  EXPECT_LT(0.5 * (1.0 - 4.0 * 0.496 * 0.496), 0.01);
  m.poisson_ratio = 0.4999999;
  EXPECT_NO_THROW(validate(m));
  EXPECT_EQ(material_warning(m).rfind("poisson_ratio 0.4999999 is above 0.495", 0), 0u) << material_warning(m);
}

}  // namespace
}  // namespace sutura::engine
