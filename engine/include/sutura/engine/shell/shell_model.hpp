#pragma once
// The interface every shell model implements. Relaxation, joining, solvers and the GUI use
// shells only through it, so any model can be plugged in without changing them (the paper's
// central claim, Sec. 1).
//
// Models are pure functions of (topology, per-element rest state, materials, state), in the
// style of libshell: no hidden state, so finite-difference tests and rest-state interpolation
// are straightforward.
//
// Degrees of freedom: dofs_per_node() = 3 (ux uy uz) or 6 (ux uy uz rx ry rz). Node n's DOFs
// are rows [n*d, n*d + d). Translational DOFs perturb x; rotational DOFs are spatial spin
// increments w applied as D <- exp([w]x) D (left/global). Gradient and Hessian are taken with
// respect to these increments at zero.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Sparse>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/material.hpp"
#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine {

/// Everything a model needs besides the state. Non-owning; all must outlive the call.
struct ShellProblem {
  const std::vector<FaceIndices>* faces = nullptr;
  const RestState* rest = nullptr;
  const std::vector<ShellMaterial>* materials = nullptr;
  const std::vector<int>* face_material = nullptr;  ///< index into materials, per face
  std::size_t num_nodes = 0;
};

/// Per-element measures for colour maps and reports.
struct ElementMeasures {
  std::vector<double> membrane_strain;   ///< max principal Green-Lagrange membrane strain, -
  std::vector<double> bending_curvature; ///< max |principal curvature change|, 1/mm
  std::vector<double> energy_density;    ///< strain energy per rest area, N/mm
};

using Triplets = std::vector<Eigen::Triplet<double>>;

class ShellModel {
 public:
  virtual ~ShellModel() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  [[nodiscard]] virtual int dofs_per_node() const = 0;

  /// Total strain energy, N*mm.
  [[nodiscard]] virtual double energy(const ShellProblem& p, const ShellState& s) const = 0;
  /// Gradient of the energy w.r.t. the DOF increments (internal force = -gradient). `g` is
  /// resized to num_nodes * dofs_per_node().
  virtual double energy_gradient(const ShellProblem& p, const ShellState& s,
                                 Eigen::VectorXd& g) const = 0;
  /// Energy, gradient and tangent stiffness (consistent linearisation of the gradient;
  /// triplets with duplicates to be summed). With `symmetric` the tangent is symmetrised
  /// (exact at equilibrium), as sparse Cholesky and CG require. Returns the energy.
  virtual double energy_gradient_hessian(const ShellProblem& p, const ShellState& s,
                                         Eigen::VectorXd& g, Triplets& K,
                                         bool symmetric = true) const = 0;
  [[nodiscard]] virtual ElementMeasures measures(const ShellProblem& p,
                                                 const ShellState& s) const = 0;
};

/// Model 1 (default): corotational flat triangle, 6 DOF per node, ANDES-OPT membrane with
/// drilling rotations + DKT bending, element-independent corotational formulation.
std::unique_ptr<ShellModel> make_corotational_shell();
/// Model 2: discrete shell, 3 DOF per node, CST St.Venant-Kirchhoff membrane + hinge bending.
std::unique_ptr<ShellModel> make_discrete_shell();

/// Applies DOF increments `du` (size num_nodes * dofs) to a state: x += du_t, D <- exp(du_r) D.
void apply_increment(ShellState& s, const Eigen::VectorXd& du, int dofs_per_node);

}  // namespace sutura::engine
