// Penalty contact (sim/contact.hpp) and its point-triangle distance.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include <Eigen/Eigenvalues>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/sim/contact.hpp"
#include "sutura/engine/sim/selection.hpp"
#include "sutura/engine/sim/static_solver.hpp"

using namespace sutura::engine;

namespace {

// A general (not axis-aligned) triangle and points well inside each feature region.
const Vec3 kT0(0.1, -0.2, 0.05), kT1(2.0, 0.1, 0.3), kT2(0.4, 1.7, -0.2);

Vec3 normal() { return (kT1 - kT0).cross(kT2 - kT0).normalized(); }

struct RegionCase {
  TriangleFeature feature;
  Vec3 point;
};

std::vector<RegionCase> region_cases() {
  const Vec3 n = normal();
  const std::array<Vec3, 3> t = {kT0, kT1, kT2};
  const Vec3 centroid = (kT0 + kT1 + kT2) / 3.0;
  std::vector<RegionCase> cases = {{TriangleFeature::Face, centroid + 0.3 * n}};
  const std::array<TriangleFeature, 3> edges = {TriangleFeature::Edge01, TriangleFeature::Edge12,
                                                TriangleFeature::Edge20};
  const std::array<TriangleFeature, 3> vertices = {TriangleFeature::Vertex0, TriangleFeature::Vertex1,
                                                   TriangleFeature::Vertex2};
  for (int k = 0; k < 3; ++k) {
    const Vec3 a = t[k], b = t[(k + 1) % 3];
    const Vec3 mid = 0.5 * (a + b);
    const Vec3 out = (b - a).cross(n).normalized();  // in-plane, away from the triangle
    cases.push_back({edges[k], mid + 0.4 * out - 0.2 * n});
    cases.push_back({vertices[k], t[k] + 0.5 * (t[k] - centroid).normalized() + 0.1 * n});
  }
  return cases;
}

std::array<Vec3, 4> unpack(const Vec12& x) {
  return {x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9)};
}

PointTriangleDistance at(const Vec12& x, bool hessian) {
  const auto p = unpack(x);
  return point_triangle_squared_distance(p[0], p[1], p[2], p[3], hessian);
}

// Contact between a triangle A (nodes 0-2) and a triangle B (nodes 3-5) whose first vertex is
// placed near A; B's other corners are far above.
struct TwoTriangles {
  std::vector<FaceIndices> faces = {{0, 1, 2}, {3, 4, 5}};
  ShellState state;
  RestState rest;
  explicit TwoTriangles(const Vec3& near) {
    state.x = {Vec3(0, 0, 0), Vec3(3, 0, 0), Vec3(0, 3, 0), near, near + Vec3(1, 0, 5), near + Vec3(0, 1, 5)};
    state.D.assign(6, Quat::Identity());
    rest = rest_from_state(faces, state);
  }
  [[nodiscard]] ShellProblem problem() const { return {&faces, &rest, nullptr, nullptr, 6}; }
};

ContactParams exact_params() {
  ContactParams p;
  p.distance = 0.5;
  p.stiffness = 2.0;
  p.project_hessian = false;
  return p;
}

double term_energy(const ContactTerm& term, const ShellState& s, int d) {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(s.x.size()) * d);
  return term.add_energy_gradient_hessian(s, d, g, nullptr);
}

// Two parallel clamped strips 10 x 2 mm at z = +gap/2 (A) and z = -gap/2 (B), pressed
// together by pressure; clamped at both ends.
struct PressedStrips {
  SurfaceMesh a, b;
  std::vector<FaceIndices> faces;
  RestState rest;
  std::vector<ShellMaterial> materials;
  std::vector<int> face_material;
  std::unique_ptr<ShellModel> model = make_corotational_shell();
  ShellSystem sys;
  ShellState state;
  std::unique_ptr<ContactTerm> contact;

  PressedStrips(double gap, double pressure, const ContactParams* params)
      : a(make_strip({10.0, 2.0, 20, 4})), b(a) {
    std::vector<Vec3> x;
    for (const Vec3& p : a.positions()) x.push_back(p + Vec3(0, 0, 0.5 * gap));
    const auto nb = static_cast<std::int32_t>(x.size());
    for (const Vec3& p : b.positions()) x.push_back(p - Vec3(0, 0, 0.5 * gap));
    faces = a.faces();
    for (const FaceIndices& f : b.faces()) faces.push_back({f[0] + nb, f[1] + nb, f[2] + nb});
    state.x = x;
    state.D.assign(x.size(), Quat::Identity());
    rest = rest_from_state(faces, state);
    ShellMaterial m;
    m.youngs_modulus = 1.0;
    m.thickness = 0.2;
    materials = {m};
    face_material.assign(faces.size(), 0);
    sys.model = model.get();
    sys.problem = ShellProblem{&faces, &rest, &materials, &face_material, x.size()};
    const auto ends = [&](double xe) {
      return select_vertices(x, SelectPlaneBand{Vec3(xe, 0, 0), Vec3(1, 0, 0), 1e-9});
    };
    sys.constraints.fix(ends(0.0), kAllDofs, x.size());
    sys.constraints.fix(ends(10.0), kAllDofs, x.size());
    PressureLoad down, up;  // strip normals are +z: negative pressure pushes A down
    for (std::size_t f = 0; f < a.num_faces(); ++f) {
      down.faces.emplace_back(f);
      up.faces.emplace_back(f + a.num_faces());
    }
    down.pressure = -pressure;
    up.pressure = pressure;
    sys.loads.pressures = {down, up};
    if (params != nullptr) {
      ContactSurface sa, sb;
      for (std::size_t f = 0; f < a.num_faces(); ++f) {
        sa.faces.emplace_back(f);
        sb.faces.emplace_back(f + a.num_faces());
      }
      contact = std::make_unique<ContactTerm>(sys.problem, std::vector<ContactSurface>{sa, sb}, *params);
      sys.terms.push_back(contact.get());
    }
  }
  PressedStrips(const PressedStrips&) = delete;

  [[nodiscard]] double mid_gap() const {  // z(A) - z(B) at the centre node of each strip
    const std::size_t centre = 2 * 21 + 10;  // row j = 2 (y = 0), column i = 10 (x = 5)
    return state.x[centre].z() - state.x[a.num_vertices() + centre].z();
  }
  // Smallest distance from a vertex of one strip to a triangle of the other (brute force).
  [[nodiscard]] double min_distance() const {
    double best = HUGE_VAL;
    const std::size_t na = a.num_vertices(), fa = a.num_faces();
    for (std::size_t v = 0; v < state.x.size(); ++v)
      for (std::size_t f = 0; f < faces.size(); ++f) {
        if ((v < na) == (f < fa)) continue;
        const auto& t = faces[f];
        best = std::min(best, std::sqrt(closest_point_on_triangle(state.x[v], state.x[t[0]], state.x[t[1]],
                                                                  state.x[t[2]])
                                            .squared_distance));
      }
    return best;
  }
};

}  // namespace

TEST(PointTriangleDistance, RegionsAndFiniteDifferences) {
  for (const RegionCase& rc : region_cases()) {
    SCOPED_TRACE(static_cast<int>(rc.feature));
    Vec12 x;
    x << rc.point, kT0, kT1, kT2;
    const PointTriangleDistance d = at(x, true);
    ASSERT_EQ(d.closest.feature, rc.feature);
    EXPECT_NEAR(d.closest.weights.sum(), 1.0, 1e-15);
    EXPECT_GE(d.closest.weights.minCoeff(), 0.0);
    // b equals the distance to the closest point, which is no farther than any corner.
    EXPECT_LE(d.closest.squared_distance, (rc.point - kT0).squaredNorm());
    const double h = 1e-6;
    for (int i = 0; i < 12; ++i) {
      Vec12 xp = x, xm = x;
      xp[i] += h, xm[i] -= h;
      const PointTriangleDistance p = at(xp, false), m = at(xm, false);
      const double fd = (p.closest.squared_distance - m.closest.squared_distance) / (2 * h);
      EXPECT_NEAR(d.gradient[i], fd, 1e-8) << "gradient " << i;
      const Vec12 fd_col = (p.gradient - m.gradient) / (2 * h);
      for (int j = 0; j < 12; ++j) EXPECT_NEAR(d.hessian(j, i), fd_col[j], 1e-7) << "hessian " << j << "," << i;
    }
    EXPECT_LT((d.hessian - d.hessian.transpose()).norm(), 1e-12 * d.hessian.norm());
  }
}

TEST(PointTriangleDistance, DegenerateTriangleUsesItsNearestEdge) {
  const PointTriangleClosest c =
      closest_point_on_triangle(Vec3(1, 1, 0), Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0));
  EXPECT_TRUE(std::isfinite(c.squared_distance));
  EXPECT_NEAR(c.squared_distance, 1.0, 1e-15);
}

TEST(Contact, EnergyGradientAndHessianMatchFiniteDifferencesInEveryRegion) {
  // B's first vertex near A's face interior, near edge 0-1 (below y = 0), near corner 0.
  const std::vector<std::pair<Vec3, TriangleFeature>> cases = {
      {Vec3(1.0, 1.0, 0.2), TriangleFeature::Face},
      {Vec3(1.5, -0.2, 0.1), TriangleFeature::Edge01},
      {Vec3(-0.25, -0.2, 0.1), TriangleFeature::Vertex0}};
  for (int d : {3, 6}) {
    for (const auto& [near, feature] : cases) {
      SCOPED_TRACE(static_cast<int>(feature));
      TwoTriangles tt(near);
      const ContactTerm term(tt.problem(), {{{FaceId(0)}}, {{FaceId(1)}}}, exact_params());
      const std::vector<ContactPair> pairs = term.pairs(tt.state);
      ASSERT_FALSE(pairs.empty());
      bool found = false;
      for (const ContactPair& p : pairs) found |= p.node == 3 && p.face == FaceId(0) && p.feature == feature;
      EXPECT_TRUE(found);

      const auto n = static_cast<Eigen::Index>(6 * d);
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
      Triplets K;
      const double e = term.add_energy_gradient_hessian(tt.state, d, g, &K);
      EXPECT_GT(e, 0.0);
      EXPECT_EQ(e, term_energy(term, tt.state, d));
      Eigen::SparseMatrix<double> H(n, n);
      H.setFromTriplets(K.begin(), K.end());
      const Eigen::MatrixXd Hd(H);
      const double h = 1e-6;
      for (int node = 0; node < 6; ++node)
        for (int k = 0; k < d; ++k) {
          const Eigen::Index i = node * d + k;
          if (k >= 3) {  // rotations: contact does not act on them
            EXPECT_EQ(g[i], 0.0);
            EXPECT_EQ(Hd.col(i).norm(), 0.0);
            continue;
          }
          ShellState sp = tt.state, sm = tt.state;
          sp.x[node][k] += h, sm.x[node][k] -= h;
          EXPECT_NEAR(g[i], (term_energy(term, sp, d) - term_energy(term, sm, d)) / (2 * h),
                      1e-7 * g.norm())
              << "gradient " << i;
          Eigen::VectorXd gp = Eigen::VectorXd::Zero(n), gm = Eigen::VectorXd::Zero(n);
          term.add_energy_gradient_hessian(sp, d, gp, nullptr);
          term.add_energy_gradient_hessian(sm, d, gm, nullptr);
          const Eigen::VectorXd fd = (gp - gm) / (2 * h);
          EXPECT_LT((Hd.col(i) - fd).norm(), 1e-6 * Hd.norm()) << "hessian column " << i;
        }
    }
  }
}

TEST(Contact, ProjectedHessianIsPositiveSemiDefiniteWithTheSameGradient) {
  TwoTriangles tt(Vec3(1.0, 1.0, 0.2));
  ContactParams projected = exact_params();
  projected.project_hessian = true;
  const ContactTerm exact(tt.problem(), {{{FaceId(0)}}, {{FaceId(1)}}}, exact_params());
  const ContactTerm psd(tt.problem(), {{{FaceId(0)}}, {{FaceId(1)}}}, projected);
  Eigen::VectorXd g1 = Eigen::VectorXd::Zero(18), g2 = Eigen::VectorXd::Zero(18);
  Triplets K1, K2;
  EXPECT_EQ(exact.add_energy_gradient_hessian(tt.state, 3, g1, &K1),
            psd.add_energy_gradient_hessian(tt.state, 3, g2, &K2));
  EXPECT_EQ(g1, g2);
  const auto dense = [](const Triplets& K) {
    Eigen::SparseMatrix<double> H(18, 18);
    H.setFromTriplets(K.begin(), K.end());
    return Eigen::MatrixXd(H);
  };
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> e1(dense(K1)), e2(dense(K2));
  EXPECT_LT(e1.eigenvalues().minCoeff(), 0.0);  // the exact one is indefinite here
  EXPECT_GE(e2.eigenvalues().minCoeff(), -1e-12 * e2.eigenvalues().maxCoeff());
}

TEST(Contact, WithoutProximityTheTermContributesExactlyNothing) {
  PressedStrips with(5.0, 1e-4, nullptr), without(5.0, 1e-4, nullptr);
  ContactParams params;
  params.distance = 0.5;
  ContactSurface sa, sb;
  for (std::size_t f = 0; f < with.a.num_faces(); ++f) {
    sa.faces.emplace_back(f);
    sb.faces.emplace_back(f + with.a.num_faces());
  }
  const ContactTerm term(with.sys.problem, {sa, sb}, params);
  with.sys.terms.push_back(&term);
  EXPECT_TRUE(term.pairs(with.state).empty());
  Eigen::VectorXd g = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(6 * with.state.x.size()), 0.25);
  Triplets K;
  EXPECT_EQ(term.add_energy_gradient_hessian(with.state, 6, g, &K), 0.0);
  EXPECT_TRUE((g.array() == 0.25).all());
  EXPECT_TRUE(K.empty());

  const DofMap map(with.sys);
  const Evaluation e1 = evaluate(with.sys, map, with.state, 1.0, true);
  const Evaluation e2 = evaluate(without.sys, map, without.state, 1.0, true);
  EXPECT_EQ(e1.internal_energy, e2.internal_energy);
  EXPECT_EQ(e1.residual, e2.residual);
  ASSERT_EQ(e1.tangent.nonZeros(), e2.tangent.nonZeros());
  EXPECT_EQ(Eigen::MatrixXd(e1.tangent), Eigen::MatrixXd(e2.tangent));
}

TEST(Contact, PressedStripsDoNotPassThroughEachOther) {
  const double gap = 1.0, pressure = 2e-4;
  StaticSolverParams solver;
  solver.load_steps = 4;
  // Without contact the strips cross (the load is large enough to matter).
  PressedStrips free(gap, pressure, nullptr);
  ASSERT_TRUE(solve_static(free.sys, free.state, solver).converged);
  EXPECT_LT(free.mid_gap(), 0.0);

  ContactParams params;
  params.distance = 0.3;
  PressedStrips pressed(gap, pressure, &params);
  const StaticResult r = solve_static(pressed.sys, pressed.state, solver);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_GT(pressed.mid_gap(), 0.5 * params.distance);
  EXPECT_GT(pressed.min_distance(), 0.5 * params.distance);
  EXPECT_LT(pressed.min_distance(), params.distance);  // they are in contact
  EXPECT_FALSE(pressed.contact->pairs(pressed.state).empty());
}

TEST(Contact, EvaluationIsBitIdenticalRunToRun) {
  ContactParams params;
  params.distance = 0.3;
  PressedStrips s(0.4, 2e-4, &params);  // start inside the activation distance
  // Shift A so that its vertices sit over B's triangle interiors, not over B's vertices.
  for (std::size_t v = 0; v < s.a.num_vertices(); ++v) s.state.x[v] += Vec3(0.13, 0.07, -0.2);
  const DofMap map(s.sys);
  const Evaluation e1 = evaluate(s.sys, map, s.state, 1.0, true);
  const Evaluation e2 = evaluate(s.sys, map, s.state, 1.0, true);
  EXPECT_FALSE(s.contact->pairs(s.state).empty());
  EXPECT_EQ(e1.internal_energy, e2.internal_energy);
  EXPECT_EQ(e1.residual, e2.residual);
  EXPECT_EQ(Eigen::MatrixXd(e1.tangent), Eigen::MatrixXd(e2.tangent));
}

TEST(Contact, LargeNestedTubesAreBitIdenticalRunToRun) {
  // 2 x 2624 vertices: above the size from which the pair search and evaluation run in
  // parallel. The inner tube (radius 4.8) sits within the activation distance of the outer.
  const SurfaceMesh outer = make_tube({5.0, 40.0, 64, 40});
  const SurfaceMesh inner = make_tube({4.8, 40.0, 64, 40});
  std::vector<FaceIndices> faces = outer.faces();
  ShellState s = state_from_mesh(outer);
  const auto n = static_cast<std::int32_t>(s.x.size());
  for (const FaceIndices& f : inner.faces()) faces.push_back({f[0] + n, f[1] + n, f[2] + n});
  for (const Vec3& p : inner.positions()) s.x.push_back(p + Vec3(0.05, 0.0, 0.3));
  s.D.assign(s.x.size(), Quat::Identity());
  const RestState rest = rest_from_state(faces, s);
  ContactSurface a, b;
  for (std::size_t f = 0; f < outer.num_faces(); ++f) {
    a.faces.emplace_back(f);
    b.faces.emplace_back(f + outer.num_faces());
  }
  ContactParams params;
  params.distance = 0.3;
  const ContactTerm term({&faces, &rest, nullptr, nullptr, s.x.size()}, {a, b}, params);
  const auto run = [&](Eigen::VectorXd& g, Triplets& K) {
    g = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(6 * s.x.size()));
    return term.add_energy_gradient_hessian(s, 6, g, &K);
  };
  Eigen::VectorXd g1, g2;
  Triplets K1, K2;
  const double e1 = run(g1, K1), e2 = run(g2, K2);
  EXPECT_GT(term.pairs(s).size(), 5000u);
  EXPECT_EQ(e1, e2);
  EXPECT_EQ(g1, g2);
  ASSERT_EQ(K1.size(), K2.size());
  for (std::size_t i = 0; i < K1.size(); ++i)
    ASSERT_TRUE(K1[i].row() == K2[i].row() && K1[i].col() == K2[i].col() && K1[i].value() == K2[i].value());
}

TEST(Contact, InvalidSetupsThrow) {
  TwoTriangles tt(Vec3(1, 1, 0.2));
  ContactParams bad;
  bad.distance = 0.0;
  EXPECT_THROW(validate(bad), InvalidArgument);
  bad = ContactParams{};
  bad.stiffness = -1.0;
  EXPECT_THROW(validate(bad), InvalidArgument);
  const ContactParams ok;
  EXPECT_THROW(ContactTerm(tt.problem(), {{{FaceId(0)}}}, ok), InvalidArgument);                  // one surface
  EXPECT_THROW(ContactTerm(tt.problem(), {{{FaceId(0)}}, {{FaceId(7)}}}, ok), InvalidArgument);   // bad face
  EXPECT_THROW(ContactTerm(tt.problem(), {{{FaceId(0)}}, {{FaceId(0)}}}, ok), InvalidArgument);   // shared nodes
  EXPECT_THROW(ContactTerm(tt.problem(), {{{FaceId(0)}}, {}}, ok), InvalidArgument);              // empty
  const ContactTerm term(tt.problem(), {{{FaceId(0)}}, {{FaceId(1)}}}, ok);
  ShellState small;
  small.x.assign(3, Vec3::Zero());
  EXPECT_THROW((void)term.pairs(small), InvalidArgument);
}
