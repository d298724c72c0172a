#pragma once
// Extension point for energies evaluated together with the shell model (contact between
// objects, later springs or soft constraints). Like the models, a term is a pure function of
// the state (libshell style): no hidden state changes between calls, so finite-difference
// tests and repeated evaluations at the same state give the same bits.
#include <Eigen/Core>

#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine {

class EnergyTerm {
 public:
  virtual ~EnergyTerm() = default;

  /// Returns the term's energy (N*mm) at `s` and ADDS its gradient to `g` (full DOF vector of
  /// size num_nodes * dofs_per_node, already sized by the caller; rows [n*d, n*d + d) belong to
  /// node n, the first three are translations) and, when `K` is non-null, appends its Hessian
  /// as triplets in the same full numbering (duplicates are summed by the assembler). Must be
  /// deterministic and must not append triplets with non-finite values.
  virtual double add_energy_gradient_hessian(const ShellState& s, int dofs_per_node,
                                             Eigen::VectorXd& g, Triplets* K) const = 0;
};

}  // namespace sutura::engine
