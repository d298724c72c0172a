#pragma once
// Shared helpers for the surgery tests: a body (mesh + state + rest) carried across edits, and
// a shell system over it.
#include <memory>

#include <gtest/gtest.h>

#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/shell_system.hpp"
#include "sutura/engine/surgery/carry.hpp"

namespace sutura::engine::testing {

struct Body {
  SurfaceMesh mesh;
  ShellState state;
  RestState rest;
  std::vector<int> face_material;
  Constraints constraints;

  explicit Body(SurfaceMesh m) : mesh(std::move(m)) {
    state = state_from_mesh(mesh);
    rest = rest_from_state(mesh, state);
    face_material.assign(mesh.num_faces(), 0);
  }
  void apply(const SurfaceMesh& new_mesh, const EditMaps& maps) {
    state = carry_state(maps, state);
    rest = carry_rest(maps, rest);
    face_material = carry_face_values(maps, face_material);
    constraints = carry_constraints(maps, constraints);
    mesh = new_mesh;
  }
};

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
