#pragma once
// Rest state stored PER ELEMENT (paper, Sec. 2.2): each triangle keeps its own rest corner
// positions and rest nodal triads, so two faces sharing a simulated vertex may have different
// rest geometry (the 1:n vertex mapping of a join), and rest states interpolate element-wise
// (relaxation, Sec. 2.3: rest(s) = lerp(y0, x0, s)).
#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

using Quat = Eigen::Quaterniond;

/// Rest geometry of one triangle.
struct ElementRest {
  /// Rest positions of the three corners (face corner order). Only the intrinsic shape
  /// matters to the element; the placement in space is arbitrary.
  std::array<Vec3, 3> X;
  /// Rest nodal triads expressed in this element's rest local frame: with the node triads
  /// D_i (global rotations carried in the state), the deformational rotation of corner k is
  /// measured against T_rest^T * D_i(rest) = Q[k]. Identity = triad aligned with the element.
  /// 3-DOF models use Q[k] * e_z as the rest nodal normal in the element frame.
  std::array<Quat, 3> Q;
};

struct RestState {
  std::vector<ElementRest> elements;  ///< one per face, same order as SurfaceMesh::faces()
};

/// Simulated state: one position and one nodal triad (rotation) per vertex. 3-DOF models
/// keep the triads unchanged.
struct ShellState {
  std::vector<Vec3> x;
  std::vector<Quat> D;
};

/// The state of a mesh at rest with identity triads: x = mesh positions, D = I.
ShellState state_from_mesh(const SurfaceMesh& mesh);

/// Rest state congruent with `state` on `mesh` (zero internal forces there): each element's
/// X from state.x and Q[k] = T_e^T D_i, with T_e the element's local frame. This is the paper's
/// y0 when taken on the joined shape x, and the stress-free reference of a fresh mesh.
RestState rest_from_state(const SurfaceMesh& mesh, const ShellState& state);
/// The same from a bare face array (throws InvalidArgument if a face references a node the
/// state does not have).
RestState rest_from_state(const std::vector<FaceIndices>& faces, const ShellState& state);

/// Element-wise interpolation, s in [0, 1]: X linearly, Q by slerp. a and b must have the same
/// number of elements (throws InvalidArgument otherwise). Cost O(F).
RestState lerp(const RestState& a, const RestState& b, double s);

/// Rest area of one element (from its rest corners), mm^2.
double rest_area(const ElementRest& e);

/// Local frame of a triangle: columns are e1 (along corner 0 -> 1), e2 = e3 x e1 (in plane),
/// e3 (unit normal, right-handed with the corner order). Non-finite for a degenerate triangle.
Eigen::Matrix3d element_frame(const Vec3& p0, const Vec3& p1, const Vec3& p2);

}  // namespace sutura::engine
