#pragma once
// External loads. All scale with the load factor lambda of the static solver.
//  - nodal forces/moments (N, N*mm),
//  - line loads along a chain of vertices (N/mm), lumped once into nodal forces by tributary
//    length on the geometry when the load is applied (a dead load),
//  - follower pressure on faces (MPa = N/mm^2, along the current face normal: depends on the
//    state and contributes a load stiffness),
//  - body force per rest area (N/mm^2, e.g. self weight of Scordelis-Lo: 90 per unit area).
#include <vector>

#include <Eigen/Core>

#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/constraints.hpp"

namespace sutura::engine {

struct NodalLoad {
  std::size_t node = 0;
  Vec3 force = Vec3::Zero();
  Vec3 moment = Vec3::Zero();  ///< needs a 6-DOF model
};

struct PressureLoad {
  std::vector<FaceId> faces;  ///< empty = every face
  double pressure = 0.0;      ///< MPa, positive along the face normal (right-hand corner order)
};

struct Loads {
  std::vector<NodalLoad> nodal;
  std::vector<PressureLoad> pressures;
  Vec3 body_force_per_area = Vec3::Zero();  ///< N/mm^2 on rest area

  [[nodiscard]] bool empty() const;
  [[nodiscard]] bool has_moments() const;
};

/// Nodal forces equivalent to `force_per_length` (N/mm) along the polyline through `chain`
/// (consecutive vertices; at least 2): each segment's load split half to each end (exact for
/// linear interpolation of a constant line load). Throws InvalidArgument for a short chain.
std::vector<NodalLoad> lump_line_load(const std::vector<Vec3>& positions,
                                      const std::vector<VertexId>& chain,
                                      const Vec3& force_per_length);

/// External force vector at load factor `lambda` (size num_nodes * dofs) and, when K is given,
/// the triplets of MINUS its derivative w.r.t. the DOFs (the follower-pressure load stiffness
/// to be added to the tangent), symmetrised. Throws InvalidArgument for moments with a
/// 3-DOF model.
void external_forces(const ShellProblem& p, const ShellState& s, const Loads& loads,
                     double lambda, int dofs_per_node, Eigen::VectorXd& f, Triplets* K);

/// Work done by the loads at load factor lambda (N*mm) when the state moves from `from` to `to`
/// (same mesh): dead nodal forces and body forces times the displacement, nodal moments times
/// the rotation vector between the triads (exact for a rotation about a fixed axis), follower
/// pressure times the change of the volume V = sum x0 . (x1 x x2) / 6 of its faces.
/// Why the volume: the pressure forces of external_forces (p A n / 3 per corner) are exactly
/// p dV/dx at every vertex whose faces are all pressurised (a closed surface, or a vessel with
/// its open ends held), so there the internal energy minus this work is the total potential
/// energy that a static equilibrium minimises, and line searches can use it as their merit.
/// At a free pressurised rim it is the volume work, a close but not exact potential.
/// Cost O(F).
double load_work(const ShellProblem& p, const ShellState& from, const ShellState& to,
                 const Loads& loads, double lambda);

/// The vertices at which the follower pressure of `loads` is not the derivative of load_work's
/// volume potential and that are free to move: the corners of every edge across which the
/// pressure jumps (an open rim of the pressurised faces, the border of a pressurised subset,
/// two different pressures meeting, or a flip of the face orientation), unless `constraints`
/// hold all three translations there. Empty: the pressure is conservative, so internal energy
/// minus load_work is the total potential energy, a stable equilibrium is its minimum, and an
/// energy minimisation (StaticSolverParams::shift_indefinite) may look for it.
/// Why edges: around a vertex, p dV/dx and the corner forces p A n / 3 differ by terms that
/// cancel pairwise across each edge with the same pressure on both sides (load_work).
/// Sorted, without repeats. Cost O(F log F).
std::vector<std::size_t> free_pressure_rim(const ShellProblem& p, const Loads& loads,
                                           const Constraints& constraints);

}  // namespace sutura::engine
