#pragma once
// The stiffness-proportional part of the dynamics' Rayleigh damping, corotated (private to
// engine/src/sim): f_d = beta Q K_d Q^T v, with K_d the tangent stiffness taken at some
// reference state and Q the nodes' rotations since (nodal_rotations.hpp), one 3x3 block per
// translation and per rotation of each node. Its reference positions are where K_d was taken
// or last re-referenced (matrix()); the dynamics factorise their step matrix there too.
//
// Why turned: K_d is not retaken every step (a tangent costs an assembly), and a stiffness
// taken before the shell rotated sees a rigid rotation since as deformation. Unturned, a strip
// swinging up by a radian under its load was held back by this spurious damping (beta K_d v
// with the membrane stiffness E t acting on the rigid motion): after 2 s it still crept
// towards its equilibrium, its tip 2 mm (27 %) short (Dynamics.HeavyStripSwingsUpToThe...).
// Turned, a rigid rotation since the reference is not damped (exactly for the rotation up to
// the step's start; the step's own increment is damped as by K_d, to first order).
//
// A node with only some of its DOFs free keeps Q = I (turning would mix free and held DOFs);
// held nodes do not enter.
#include <Eigen/Sparse>
#include <vector>

#include "nodal_rotations.hpp"
#include "sutura/engine/sim/shell_system.hpp"

namespace sutura::engine::detail {

class CorotatedDamping {
 public:
  /// Bend since the reference (turn_to; rad between neighbouring nodes) past which K_d is
  /// retaken. Why: turned node by node, a stiffness taken before the shell bent still damps a
  /// rigid rotation of the bent shape, in proportion to the bend times the membrane stiffness
  /// (E t, against E t^3/12 for bending). The heavy strip of
  /// Dynamics.HeavyStripSwingsUpToTheStaticEquilibriumThroughLargeRotations settles with any
  /// value from 0.002 to 0.01 rad; with K_d retaken only where the step matrix had to be
  /// rebuilt at a step's start, its tip was still 0.8 mm short after 2 s. 0.003 retakes it
  /// once in the 50 steps of the benchmark tube (bench_shell BM_DynamicsStep).
  static constexpr double kRetakeBend = 3e-3;

  CorotatedDamping(const ShellSystem& sys, const DofMap& map);

  [[nodiscard]] bool empty() const { return K_.rows() == 0; }

  /// K_d := `tangent` (free x free, symmetric), taken at node positions `x`; Q := I.
  void reset(const Eigen::SparseMatrix<double>& tangent, const std::vector<Vec3>& x);

  /// Q := the nodes' rotations from the reference to `x`. Called at the start of a step, so
  /// that the damping force stays linear in the step's increment. Returns how far the shell
  /// bent since the reference (NodalRotations::compute; 0 when empty): past kRetakeBend the
  /// caller should take K_d anew. Cost: NodalRotations::compute.
  double turn_to(const std::vector<Vec3>& x);

  /// y = Q K_d Q^T v (v, y over the free DOFs). Cost O(nnz(K_d)), parallel.
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;

  /// Q K_d Q^T as a matrix (for a step matrix). Forming it makes the positions of the last
  /// turn_to the new reference (Q := I), so apply() is unchanged up to round-off. Cost: two
  /// sparse products when Q != I, none otherwise.
  const Eigen::SparseMatrix<double>& matrix();

  /// Whether Q is not the identity (turn_to since the last reset() or matrix()).
  [[nodiscard]] bool turned() const { return turned_; }

  /// v := Q v, or Q^T v with `transpose` (v over the free DOFs). The dynamics turn their
  /// reused step matrix with it too (A^-1 ~ Q A_ref^-1 Q^T): a step matrix factorised before
  /// the shell rotated is stale by the rotation, its damping part since it is turned, its
  /// stiffness part since the elements turned. Cost O(nodes).
  void turn(bool transpose, Eigen::VectorXd& v) const;

 private:
  void restart_rotations();  // Q := I

  NodalRotations rings_;
  int dofs_per_node_;
  // Per node: the free index of its first DOF if all its DOFs are free, else -1.
  std::vector<int> block_;
  Eigen::SparseMatrix<double> K_;
  std::vector<Vec3> reference_;  // positions where K_ was taken
  std::vector<Vec3> turned_to_;  // positions of the last turn_to
  std::vector<Eigen::Matrix3d> Q_;  // also the start of the next turn_to's iteration
  bool turned_ = false;  // Q_ is not (taken as) the identity
  mutable Eigen::VectorXd scratch_;
};

}  // namespace sutura::engine::detail
