// Per-element rest states (see rest_state.hpp). Cost O(F) (O(V) for state_from_mesh).
#include <string>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine {

ShellState state_from_mesh(const SurfaceMesh& mesh) {
  ShellState s;
  s.x = mesh.positions();
  s.D.assign(s.x.size(), Quat::Identity());
  return s;
}

RestState rest_from_state(const std::vector<FaceIndices>& faces, const ShellState& state) {
  RestState rest;
  rest.elements.resize(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    ElementRest& e = rest.elements[f];
    for (int k = 0; k < 3; ++k) {
      const auto v = faces[f][k];
      if (v < 0 || static_cast<std::size_t>(v) >= state.x.size() ||
          static_cast<std::size_t>(v) >= state.D.size())
        throw InvalidArgument("rest_from_state: face " + std::to_string(f) + " references node " +
                              std::to_string(v) + " but the state has " +
                              std::to_string(state.x.size()) + " positions and " +
                              std::to_string(state.D.size()) + " triads");
      e.X[k] = state.x[v];
    }
    const Quat frame_inv = Quat(element_frame(e.X[0], e.X[1], e.X[2])).conjugate();
    for (int k = 0; k < 3; ++k) e.Q[k] = (frame_inv * state.D[faces[f][k]]).normalized();
  }
  return rest;
}

RestState rest_from_state(const SurfaceMesh& mesh, const ShellState& state) {
  return rest_from_state(mesh.faces(), state);
}

double rest_area(const ElementRest& e) {
  return 0.5 * (e.X[1] - e.X[0]).cross(e.X[2] - e.X[0]).norm();
}

RestState lerp(const RestState& a, const RestState& b, double s) {
  if (a.elements.size() != b.elements.size())
    throw InvalidArgument("lerp of rest states: " + std::to_string(a.elements.size()) + " vs " +
                          std::to_string(b.elements.size()) + " elements");
  RestState r;
  r.elements.resize(a.elements.size());
  for (std::size_t f = 0; f < a.elements.size(); ++f) {
    const ElementRest& ea = a.elements[f];
    const ElementRest& eb = b.elements[f];
    for (int k = 0; k < 3; ++k) {
      r.elements[f].X[k] = (1.0 - s) * ea.X[k] + s * eb.X[k];
      // Eigen's slerp follows the shorter arc (it flips the sign of b when a.b < 0).
      r.elements[f].Q[k] = ea.Q[k].slerp(s, eb.Q[k]).normalized();
    }
  }
  return r;
}

Eigen::Matrix3d element_frame(const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const Vec3 e1 = (p1 - p0).normalized();
  const Vec3 e3 = (p1 - p0).cross(p2 - p0).normalized();
  Eigen::Matrix3d T;
  T.col(0) = e1;
  T.col(1) = e3.cross(e1);
  T.col(2) = e3;
  return T;
}

}  // namespace sutura::engine
