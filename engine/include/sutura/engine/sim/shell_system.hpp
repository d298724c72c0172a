#pragma once
// A simulation problem: the shell model, its problem data (faces, per-element rest state,
// materials), constraints and loads. Several objects can be simulated together by merging
// them into one problem with disjoint node ranges.
//
// Residual convention: r(u) = g_int(u) - f_ext(u, lambda), equilibrium at r = 0; fixed DOFs
// are eliminated (the reduced system only has free DOFs).
#include <vector>

#include <Eigen/Sparse>

#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/constraints.hpp"
#include "sutura/engine/sim/energy_term.hpp"
#include "sutura/engine/sim/loads.hpp"
#include "sutura/engine/sim/tangent_assembler.hpp"

namespace sutura::engine {

struct ShellSystem {
  const ShellModel* model = nullptr;
  ShellProblem problem;
  Constraints constraints;
  Loads loads;        ///< scaled by the load factor lambda
  Loads fixed_loads;  ///< always at full value (loads already brought to equilibrium earlier)
  /// Extra energies added to the model's in evaluate() (e.g. contact between objects), in this
  /// order. Non-owning: each must outlive every use of the system.
  std::vector<const EnergyTerm*> terms;

  [[nodiscard]] int dofs_per_node() const { return model->dofs_per_node(); }
  [[nodiscard]] std::size_t num_dofs() const { return problem.num_nodes * dofs_per_node(); }
};

/// Maps full DOF indices to the free (unconstrained) ones.
struct DofMap {
  std::vector<int> full_to_free;  ///< -1 for fixed DOFs
  std::vector<int> free_to_full;
  explicit DofMap(const ShellSystem& sys);
  [[nodiscard]] std::size_t num_free() const { return free_to_full.size(); }
  [[nodiscard]] Eigen::VectorXd restrict(const Eigen::VectorXd& full) const;
  [[nodiscard]] Eigen::VectorXd expand(const Eigen::VectorXd& free) const;  ///< zeros at fixed
};

/// Energy/residual/tangent evaluation on the free DOFs.
struct Evaluation {
  double internal_energy = 0.0;  ///< N*mm: the model's strain energy plus every extra term's
  Eigen::VectorXd residual;      ///< free DOFs, N (or N*mm for rotations)
  double external_norm = 0.0;    ///< |f_ext| over free DOFs (reference for tolerances)
  Eigen::SparseMatrix<double> tangent;  ///< free x free, only when requested
};

/// Computes the residual (and tangent) at load factor lambda. `load_stiffness` adds the
/// follower-pressure load stiffness to the tangent (off for a classical linear analysis).
/// Cost: one model evaluation, O(F), plus the extra terms, plus sparse assembly when the
/// tangent is requested; pass the same `assembler` to repeated calls so the sparsity pattern is
/// built only once (it is rebuilt whenever a term's triplet structure changes, e.g. when the
/// set of contact pairs changes).
Evaluation evaluate(const ShellSystem& sys, const DofMap& map, const ShellState& s, double lambda,
                    bool with_tangent, bool load_stiffness = true,
                    TangentAssembler* assembler = nullptr);

/// Work of the system's loads (at load factor lambda) and fixed loads (at full value) when the
/// state moves from `from` to `to` (load_work). With it, internal energy minus work is the total
/// potential energy whose decrease a line search demands. Cost O(F).
double external_work(const ShellSystem& sys, const ShellState& from, const ShellState& to,
                     double lambda);

/// Smallest ratio of a triangle's current area to its rest area (from the per-element rest
/// corners), over all faces; +inf without faces. Solvers use it to reject states in which an
/// element has collapsed: the flat corotational elements do not resist being squashed through
/// zero area, so without the test a crumpling region collapses elements instead of wrinkling.
/// Cost O(F).
double min_area_ratio(const ShellProblem& problem, const ShellState& s);

/// Lumped nodal masses (per full DOF): translational rho*t*A/3 per corner; rotational
/// rho*t*A/3 * max(t^2/12, A/12) so rotations are not massless (no effect on statics).
Eigen::VectorXd lumped_mass(const ShellSystem& sys);

}  // namespace sutura::engine
