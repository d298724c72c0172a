// The attribute layer: every channel of SurfaceAttributes follows every edit (incise, join,
// resect, append) by the rule its header states, checked against the edit's own maps.
#include "sutura/engine/surgery/surface_attributes.hpp"

#include <algorithm>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/join.hpp"
#include "sutura/engine/surgery/resect.hpp"

namespace sutura::engine {
namespace {

constexpr int kDofs = 6;

// A tube with every channel set to something an edit could lose: displaced state with turned
// triads, a pending y0 part-way relaxed, two materials, fixed vertices at one end, nodal and
// pressure loads (applied and pending), a velocity, a reference, and an incision mark.
struct Fixture {
  SurfaceMesh mesh = make_tube({3.0, 30.0, 24, 30});
  SurfaceAttributes a = attributes_at_rest(mesh);

  Fixture() {
    const std::size_t nv = mesh.num_vertices(), nf = mesh.num_faces();
    for (std::size_t v = 0; v < nv; ++v) {
      a.state.x[v] += Vec3(0.01 * double(v % 7), 0.0, 0.02 * double(v % 5));
      a.state.D[v] = Quat(Eigen::AngleAxisd(0.001 * double(v % 11), Vec3::UnitX()));
    }
    a.relax_from = rest_from_state(mesh, a.state);
    a.relax_s = 0.25;
    a.materials.push_back(ShellMaterial{});
    a.materials.back().thickness = 0.7;
    for (std::size_t f = 0; f < nf; ++f) a.face_material[f] = int(f % 2);
    a.constraints.fixed.assign(nv, 0);
    for (std::size_t v = 0; v < nv; ++v)
      if (mesh.position(VertexId(v)).z() < 1e-9) a.constraints.fixed[v] = 0x3f;
    a.applied_loads.nodal.push_back({5, Vec3(0, 0, 1), Vec3::Zero()});
    a.applied_loads.pressures.push_back({{}, 0.01});
    a.pending_loads.nodal.push_back({nv - 3, Vec3(1, 0, 0), Vec3::Zero()});
    a.pending_loads.pressures.push_back({{FaceId(0), FaceId(nf / 2), FaceId(nf - 1)}, 0.02});
    a.pending_factor = 0.5;
    a.velocity.resize(static_cast<Eigen::Index>(nv * kDofs));
    for (Eigen::Index i = 0; i < a.velocity.size(); ++i) a.velocity[i] = 0.001 * double(i % 13);
    a.state_model = "corotational";
    a.marks.incisions.push_back({VertexId(24 * 10), VertexId(24 * 11), VertexId(24 * 12)});
    mesh.set_positions(a.state.x);
    check_attributes(mesh, a);
  }
};

// Every per-vertex and per-face channel of `after` agrees with `before` through `maps`.
void expect_carried(const Fixture& before, const SurfaceMesh& mesh, const SurfaceAttributes& after,
                    const EditMaps& maps) {
  ASSERT_NO_THROW(check_attributes(mesh, after));
  const SurfaceAttributes& b = before.a;
  ASSERT_EQ(after.velocity.size(), static_cast<Eigen::Index>(mesh.num_vertices() * kDofs));
  for (std::size_t v = 0; v < mesh.num_vertices(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    Vec3 x = Vec3::Zero(), ref = Vec3::Zero();
    Eigen::Matrix<double, kDofs, 1> vel = Eigen::Matrix<double, kDofs, 1>::Zero();
    for (std::size_t i = 0; i < o.parents.size(); ++i) {
      const std::size_t p = o.parents[i].index();
      x += o.weights[i] * b.state.x[p];
      ref += o.weights[i] * b.reference[p];
      vel += o.weights[i] * b.velocity.segment<kDofs>(static_cast<Eigen::Index>(p * kDofs));
    }
    EXPECT_LT((after.state.x[v] - x).norm(), 1e-12) << "state.x of vertex " << v;
    EXPECT_LT((mesh.position(VertexId(v)) - x).norm(), 1e-12) << "mesh position " << v;
    EXPECT_LT((after.reference[v] - ref).norm(), 1e-12) << "reference of vertex " << v;
    EXPECT_LT((after.velocity.segment<kDofs>(static_cast<Eigen::Index>(v * kDofs)) - vel).norm(),
              1e-12)
        << "velocity of vertex " << v;
    if (o.parents.size() == 1) {
      const std::size_t p = o.parents[0].index();
      EXPECT_TRUE(after.state.D[v].isApprox(b.state.D[p], 1e-14)) << "triad of vertex " << v;
      EXPECT_EQ(after.constraints.fixed[v], b.constraints.fixed[p]) << "constraint of " << v;
    }
  }
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const FaceOrigin& o = maps.faces[f];
    EXPECT_EQ(after.face_material[f], b.face_material[o.parent.index()]) << "face " << f;
    if (o.bary == Eigen::Matrix3d::Identity()) {
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(after.rest.elements[f].X[k], b.rest.elements[o.parent.index()].X[k]);
        EXPECT_EQ(after.relax_from->elements[f].X[k],
                  b.relax_from->elements[o.parent.index()].X[k]);
      }
    }
  }
  // Per-surface channels are kept as they were.
  EXPECT_EQ(after.materials.size(), b.materials.size());
  EXPECT_EQ(after.materials.back().thickness, b.materials.back().thickness);
  EXPECT_EQ(after.relax_s, b.relax_s);
  EXPECT_EQ(after.pending_factor, b.pending_factor);
  EXPECT_EQ(after.state_model, b.state_model);
  ASSERT_TRUE(after.relax_from.has_value());
  // Loads: the whole-surface pressure stays whole-surface; a face-list pressure follows its
  // faces; nodal loads follow their vertices.
  ASSERT_EQ(after.applied_loads.pressures.size(), 1u);
  EXPECT_TRUE(after.applied_loads.pressures[0].faces.empty());
  ASSERT_EQ(after.pending_loads.pressures.size(), 1u);
  EXPECT_GE(after.pending_loads.pressures[0].faces.size(), 1u);
  const auto& old_set = b.pending_loads.pressures[0].faces;
  for (const FaceId f : after.pending_loads.pressures[0].faces) {
    const FaceId parent = maps.faces[f.index()].parent;
    EXPECT_NE(std::find(old_set.begin(), old_set.end(), parent), old_set.end())
        << "pressure moved to face " << f.index() << " from " << parent.index();
  }
  for (const Loads* l : {&after.applied_loads, &after.pending_loads})
    for (const NodalLoad& n : l->nodal) {
      const Loads& old = l == &after.applied_loads ? b.applied_loads : b.pending_loads;
      const std::size_t old_node = old.nodal.front().node;
      bool descends = false;
      for (const VertexId p : maps.vertices[n.node].parents) descends |= p.index() == old_node;
      EXPECT_TRUE(descends) << "nodal load moved to vertex " << n.node;
    }
}

// The fixture after a slit across its tube, over the rings of its incision mark; `r` is the
// incision.
Fixture slit(const Fixture& fx, IncisionResult& r) {
  r = incise(fx.mesh, {Vec3(3.0, 0.0, 12.2), Vec3(2.121, 2.121, 14.9), Vec3(0.0, 3.0, 17.7)});
  Fixture out = fx;
  apply_edit(out.mesh, out.a, r.mesh, r.maps);
  return out;
}

TEST(SurfaceAttributes, AnIncisionCarriesEveryChannel) {
  const Fixture fx;
  IncisionResult r;
  const Fixture cut = slit(fx, r);
  expect_carried(fx, cut.mesh, cut.a, r.maps);
  EXPECT_EQ(cut.a.marks.incisions.size(), 1u);  // the old mark follows its vertices
  EXPECT_EQ(cut.a.applied_loads.nodal.size(), 1u);
  EXPECT_EQ(cut.a.pending_loads.nodal.size(), 1u);
}

TEST(SurfaceAttributes, AJoinCarriesEveryChannelAndMergesVelocities) {
  IncisionResult cut;
  const Fixture cut_fx = slit(Fixture{}, cut);
  SurfaceMesh mesh = cut_fx.mesh;
  SurfaceAttributes a = cut_fx.a;
  // Re-join the slit (left lip against the right lip, in boundary direction).
  const BoundaryChain left{cut.left, false};
  const BoundaryChain right{{cut.right.rbegin(), cut.right.rend()}, false};
  const JoinResult j = join(mesh, {{left, right}});
  apply_edit(mesh, a, j.mesh, j.maps);
  expect_carried(cut_fx, mesh, a, j.maps);
  EXPECT_EQ(mesh.boundary_loops().size(), 2u);  // the slit is closed: the tube's two ends
}

TEST(SurfaceAttributes, AResectionCarriesEveryChannelAndDropsWhatItRemoves) {
  Fixture fx;
  const ResectionResult r =
      resect(fx.mesh, {{Vec3(0, 0, 10.5), Vec3(0, 0, 1)}, {Vec3(0, 0, 15.5), Vec3(0, 0, -1)}},
             Vec3(0, 0, 13));
  SurfaceMesh mesh = fx.mesh;
  SurfaceAttributes a = fx.a;
  apply_edit(mesh, a, r.mesh, r.maps);
  expect_carried(fx, mesh, a, r.maps);
  // The incision mark ran from z = 10 into the removed band (10.5 to 15.5): what is left of it
  // ends on the cut.
  ASSERT_EQ(a.marks.incisions.size(), 1u);
  for (const VertexId v : a.marks.incisions[0]) EXPECT_LE(mesh.position(v).z(), 10.5 + 1e-9);
}

TEST(SurfaceAttributes, AppendingAComponentExtendsEveryChannelAtRest) {
  Fixture fx;
  SurfaceMesh mesh = fx.mesh;
  SurfaceAttributes a = fx.a;
  const SurfaceMesh part = make_strip({4.0, 2.0, 4, 2});
  ShellMaterial patch;
  patch.thickness = 0.3;
  const std::size_t off = append_component(mesh, a, part, part, patch);
  EXPECT_EQ(off, fx.mesh.num_vertices());
  ASSERT_NO_THROW(check_attributes(mesh, a));
  EXPECT_EQ(a.materials.size(), fx.a.materials.size() + 1);
  EXPECT_EQ(a.face_material.back(), int(a.materials.size() - 1));
  for (std::size_t v = off; v < mesh.num_vertices(); ++v) {
    EXPECT_EQ(a.constraints.fixed[v], 0);
    EXPECT_EQ(a.state.x[v], part.position(VertexId(v - off)));
    EXPECT_EQ(a.reference[v], part.position(VertexId(v - off)));
    EXPECT_TRUE(a.velocity.segment<kDofs>(static_cast<Eigen::Index>(v * kDofs)).isZero());
  }
  // The old part keeps everything bit for bit.
  for (std::size_t v = 0; v < off; ++v) EXPECT_EQ(a.state.x[v], fx.a.state.x[v]);
  EXPECT_EQ(a.velocity.head(fx.a.velocity.size()), fx.a.velocity);
  EXPECT_EQ(a.relax_from->elements.size(), mesh.num_faces());
  EXPECT_EQ(a.marks.incisions, fx.a.marks.incisions);
  EXPECT_EQ(a.relax_s, fx.a.relax_s);
}

TEST(SurfaceAttributes, CheckNamesTheChannelOfTheWrongSize) {
  Fixture fx;
  fx.a.reference.pop_back();
  try {
    check_attributes(fx.mesh, fx.a);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'reference'"), std::string::npos) << e.what();
  }
  Fixture fy;
  fy.a.pending_loads.nodal.push_back({fy.mesh.num_vertices(), Vec3::Zero(), Vec3::Zero()});
  EXPECT_THROW(check_attributes(fy.mesh, fy.a), Error);
}

TEST(SurfaceAttributes, AnEditWhoseMapsDoNotFitIsRefusedAndChangesNothing) {
  Fixture fx;
  SurfaceMesh mesh = fx.mesh;
  SurfaceAttributes a = fx.a;
  const EditMaps wrong = EditMaps::identity(3, 1);
  EXPECT_THROW(apply_edit(mesh, a, fx.mesh, wrong), InvalidArgument);
  EXPECT_EQ(mesh.num_vertices(), fx.mesh.num_vertices());
  EXPECT_EQ(a.state.x, fx.a.state.x);
}

}  // namespace
}  // namespace sutura::engine
