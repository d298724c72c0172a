#include "sutura/engine/sim/shell_system.hpp"

#include <algorithm>
#include <limits>

namespace sutura::engine {

DofMap::DofMap(const ShellSystem& sys) {
  const int d = sys.dofs_per_node();
  full_to_free.assign(sys.num_dofs(), -1);
  for (std::size_t n = 0; n < sys.problem.num_nodes; ++n)
    for (int k = 0; k < d; ++k) {
      if (sys.constraints.is_fixed(n, k)) continue;
      full_to_free[n * d + k] = static_cast<int>(free_to_full.size());
      free_to_full.push_back(static_cast<int>(n * d + k));
    }
}

Eigen::VectorXd DofMap::restrict(const Eigen::VectorXd& full) const {
  Eigen::VectorXd r(static_cast<Eigen::Index>(free_to_full.size()));
  for (std::size_t i = 0; i < free_to_full.size(); ++i) r[i] = full[free_to_full[i]];
  return r;
}

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& free) const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(full_to_free.size()));
  for (std::size_t i = 0; i < free_to_full.size(); ++i) f[free_to_full[i]] = free[i];
  return f;
}

Evaluation evaluate(const ShellSystem& sys, const DofMap& map, const ShellState& s, double lambda,
                    bool with_tangent, bool load_stiffness, TangentAssembler* assembler) {
  Evaluation ev;
  Eigen::VectorXd g, f;
  TangentAssembler local;
  TangentAssembler& as = assembler != nullptr ? *assembler : local;
  Triplets& K = as.buffer();
  if (with_tangent)
    ev.internal_energy = sys.model->energy_gradient_hessian(sys.problem, s, g, K, true);
  else
    ev.internal_energy = sys.model->energy_gradient(sys.problem, s, g);
  for (const EnergyTerm* term : sys.terms)
    ev.internal_energy +=
        term->add_energy_gradient_hessian(s, sys.dofs_per_node(), g, with_tangent ? &K : nullptr);
  external_forces(sys.problem, s, sys.loads, lambda, sys.dofs_per_node(), f,
                  with_tangent && load_stiffness ? &K : nullptr);
  if (!sys.fixed_loads.empty()) {
    Eigen::VectorXd f_fixed;
    external_forces(sys.problem, s, sys.fixed_loads, 1.0, sys.dofs_per_node(), f_fixed,
                    with_tangent && load_stiffness ? &K : nullptr);
    f += f_fixed;
  }
  ev.residual = map.restrict(g - f);
  ev.external_norm = map.restrict(f).norm();
  if (with_tangent)
    as.assemble(K, map.full_to_free, static_cast<Eigen::Index>(map.num_free()), ev.tangent);
  return ev;
}

double external_work(const ShellSystem& sys, const ShellState& from, const ShellState& to,
                     double lambda) {
  double work = load_work(sys.problem, from, to, sys.loads, lambda);
  if (!sys.fixed_loads.empty()) work += load_work(sys.problem, from, to, sys.fixed_loads, 1.0);
  return work;
}

double min_area_ratio(const ShellProblem& p, const ShellState& s) {
  double ratio = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < p.faces->size(); ++f) {
    const FaceIndices& face = (*p.faces)[f];
    const double rest = rest_area(p.rest->elements[f]);
    const Vec3& a = s.x[face[0]];
    const double now = 0.5 * (s.x[face[1]] - a).cross(s.x[face[2]] - a).norm();
    if (rest > 0.0) ratio = std::min(ratio, now / rest);
  }
  return ratio;
}

Eigen::VectorXd lumped_mass(const ShellSystem& sys) {
  const int d = sys.dofs_per_node();
  Eigen::VectorXd m = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sys.num_dofs()));
  const auto& faces = *sys.problem.faces;
  for (std::size_t e = 0; e < faces.size(); ++e) {
    const ShellMaterial& mat = (*sys.problem.materials)[(*sys.problem.face_material)[e]];
    const double area = rest_area(sys.problem.rest->elements[e]);
    const double mt = mat.density * mat.thickness * area / 3.0;
    // Rotary inertia of a plate slice (t^2/12), floored by an in-plane term (A/12) so the
    // drilling rotation is not nearly massless; it only shapes the transient.
    const double mr = mt * std::max(mat.thickness * mat.thickness / 12.0, area / 12.0);
    for (int k = 0; k < 3; ++k) {
      const auto n = static_cast<Eigen::Index>(faces[e][k]) * d;
      for (int i = 0; i < 3; ++i) m[n + i] += mt;
      for (int i = 3; i < d; ++i) m[n + i] += mr;
    }
  }
  return m;
}

}  // namespace sutura::engine
