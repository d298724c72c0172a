#pragma once
// Collapse barrier: an energy that resists squashing a triangle towards zero area.
//
// Why: the flat corotational elements (model 1) measure strain in a frame fitted to the
// current triangle, so a triangle squashed through zero area costs only a finite, linear-
// elastic energy and can invert. Where tissue is gathered or creased more finely than the mesh
// can wrinkle (a flap's tip folded into an incision, a seam joining chains of different
// lengths), the energy minimum then lies at collapsed elements and no meaningful equilibrium
// exists. Real tissue resists such compression without bound; this term restores that, and
// only there: per face
//   E_f = k_f A0_f b(A_f / A0_f),   b(r) = -(r - r0)^2 ln(r / r0) for r < r0, 0 otherwise,
// the barrier of Li et al., "Incremental Potential Contact" (2020), applied to the area ratio:
// zero with zero first and second derivative at r0 (C2: Newton does not notice it switching
// on) and infinite as r -> 0. k_f = factor * E_f t_f (the face's membrane stiffness, N/mm),
// A0_f the face's rest area (from the per-element rest corners, read at every call, so it
// follows a relaxation). It acts on translations only. With r0 = 0.25 it is inactive unless a
// triangle has lost three quarters of its area, so ordinary shapes are unaffected.
#include "sutura/engine/sim/energy_term.hpp"

namespace sutura::engine {

struct AreaBarrierParams {
  double activation = 0.25;  ///< r0: area ratio below which the barrier acts, in (0, 1)
  double factor = 1.0;       ///< stiffness k = factor * E t, > 0
};

class AreaBarrier final : public EnergyTerm {
 public:
  /// `problem` must outlive the term (its faces, rest state and materials are read at every
  /// call). Throws InvalidArgument for parameters out of range.
  AreaBarrier(const ShellProblem& problem, const AreaBarrierParams& params);

  double add_energy_gradient_hessian(const ShellState& s, int dofs_per_node, Eigen::VectorXd& g,
                                     Triplets* K) const override;

 private:
  ShellProblem problem_;
  AreaBarrierParams params_;
};

}  // namespace sutura::engine
