#pragma once
// Shared helpers for the surgery tests: a body (mesh + attributes) carried across edits, and
// a shell system over it.
#include <memory>

#include <gtest/gtest.h>

#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/shell_system.hpp"
#include "sutura/engine/surgery/carry.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/surface_attributes.hpp"

namespace sutura::engine::testing {

// Engine attributes with their mesh; edits go through the engine's apply_edit, the same path
// as the app's.
struct Body : SurfaceAttributes {
  SurfaceMesh mesh;

  explicit Body(SurfaceMesh m) : SurfaceAttributes(attributes_at_rest(m)), mesh(std::move(m)) {}
  void apply(const SurfaceMesh& new_mesh, const EditMaps& maps) {
    apply_edit(mesh, *this, new_mesh, maps);
  }
};

// A vertex origin of an edit's maps, parents given as plain indices.
inline VertexOrigin vertex_origin(VertexOriginKind kind, std::vector<int> parents,
                                  std::vector<double> weights) {
  VertexOrigin o;
  o.kind = kind;
  for (int p : parents) o.parents.emplace_back(p);
  o.weights = std::move(weights);
  return o;
}

// Incision parameters of the paper's prototype: snapped to mesh edges.
inline IncisionParams snapped() {
  IncisionParams p;
  p.mode = IncisionMode::SnapToEdges;
  return p;
}

inline ShellMaterial soft_material(double nu = 0.3) {
  ShellMaterial m;
  m.youngs_modulus = 1.0;
  m.poisson_ratio = nu;
  m.thickness = 0.2;
  return m;
}

// Energy and gradient norm of a body in its carried rest state.
inline std::pair<double, double> energy_and_force(const ShellModel& model, const Body& b) {
  const std::vector<ShellMaterial> mats{soft_material()};
  const ShellProblem p{&b.mesh.faces(), &b.rest, &mats, &b.face_material, b.mesh.num_vertices()};
  Eigen::VectorXd g;
  const double e = model.energy_gradient(p, b.state, g);
  return {e, g.norm()};
}

}  // namespace sutura::engine::testing
