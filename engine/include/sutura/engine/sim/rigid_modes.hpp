#pragma once
// Rigid-body motions left free by a body's constraints: where one remains, a static
// equilibrium is not unique (the tangent is singular along it) and a static solve must refuse
// instead of reporting whatever position the factorisation's round-off picks.
#include <string>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/sim/constraints.hpp"

namespace sutura::engine {

/// The velocity field v(x) = translation + rotation x (x - point) (rotation in rad per unit
/// time, zero for a translation).
struct RigidMotion {
  Vec3 translation = Vec3::Zero();
  Vec3 rotation = Vec3::Zero();
  Vec3 point = Vec3::Zero();
  /// "translation along (0, 0, 1)" or "rotation about the axis (0, 0, 1) through (1, 2, 3)"
  /// (a screw motion is named by its rotation), directions rounded to 3 digits.
  [[nodiscard]] std::string describe() const;
};

/// A basis of the rigid-body motions of the nodes `x` that no fixed DOF of `c` restrains: the
/// null space of the fixed DOFs' rows of the six rigid modes (a fixed translation DOF restrains
/// the motions that move its node along it; a fixed rotation DOF, the rotations about its
/// axis). Empty when every rigid motion is restrained; all six when nothing is fixed. The
/// rotations are scaled by the body's size, so "free" means a smallest singular value below
/// 1e-6 of that of one fully held node: numerically free (three nodes nearly in line restrain
/// the rotation about that line). Deterministic. Cost O(V + fixed DOFs) (the body's centre and size).
std::vector<RigidMotion> free_rigid_motions(const std::vector<Vec3>& x, const Constraints& c);

}  // namespace sutura::engine
