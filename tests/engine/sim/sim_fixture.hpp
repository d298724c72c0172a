#pragma once
// A clamped cantilever strip as a ShellSystem, shared by the solver tests.
#include <memory>

#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/selection.hpp"
#include "sutura/engine/sim/shell_system.hpp"

namespace sutura::engine::testing {

struct Cantilever {
  SurfaceMesh mesh;
  std::vector<FaceIndices> faces;
  RestState rest;
  std::vector<ShellMaterial> materials;
  std::vector<int> face_material;
  std::unique_ptr<ShellModel> model;
  ShellSystem sys;
  ShellState state;

  // Strip L x b, thickness t, E, nu = 0, clamped at x = 0, total tip force `tip` along +z.
  Cantilever(std::unique_ptr<ShellModel> m, double tip, int nl = 20, int nw = 2, double L = 10.0,
             double b = 1.0, double t = 0.1, double E = 1.2e6)
      : mesh(make_strip({L, b, nl, nw})), model(std::move(m)) {
    faces = mesh.faces();
    state = state_from_mesh(mesh);
    rest = rest_from_state(mesh, state);
    ShellMaterial mat;
    mat.youngs_modulus = E;
    mat.poisson_ratio = 0.0;
    mat.thickness = t;
    materials = {mat};
    face_material.assign(faces.size(), 0);
    sys.model = model.get();
    sys.problem = ShellProblem{&faces, &rest, &materials, &face_material, mesh.num_vertices()};
    const auto root = select_vertices(mesh.positions(), SelectPlaneBand{Vec3(0, 0, 0), Vec3(1, 0, 0), 1e-9});
    sys.constraints.fix(root, kAllDofs, mesh.num_vertices());
    const auto tipv = select_vertices(mesh.positions(), SelectPlaneBand{Vec3(L, 0, 0), Vec3(1, 0, 0), 1e-9});
    for (auto v : tipv) sys.loads.nodal.push_back({v.index(), Vec3(0, 0, tip / tipv.size()), Vec3::Zero()});
  }
  Cantilever(const Cantilever&) = delete;

  [[nodiscard]] Vec3 tip_displacement() const {
    const auto v = select_vertices(mesh.positions(), SelectNearest{{Vec3(mesh.bounds().max().x(), 0, 0)}})[0];
    return state.x[v.index()] - mesh.position(v);
  }
};

}  // namespace sutura::engine::testing
