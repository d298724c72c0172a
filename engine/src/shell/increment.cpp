// apply_increment (see shell_model.hpp): x += du_t, D <- exp([du_r]x) D with the exact
// exponential map (quaternion form), then renormalised so round-off cannot accumulate.
// Cost O(num_nodes).
#include <string>

#include "so3.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine {

void apply_increment(ShellState& s, const Eigen::VectorXd& du, int dofs_per_node) {
  if (dofs_per_node != 3 && dofs_per_node != 6)
    throw InvalidArgument("apply_increment: dofs_per_node = " + std::to_string(dofs_per_node) +
                          " (must be 3 or 6)");
  const std::size_t n = s.x.size();
  const auto d = static_cast<std::size_t>(dofs_per_node);
  if (static_cast<std::size_t>(du.size()) != n * d)
    throw InvalidArgument("apply_increment: increment has " + std::to_string(du.size()) +
                          " entries for " + std::to_string(n) + " nodes x " +
                          std::to_string(d) + " DOFs");
  if (d == 6 && s.D.size() != n)
    throw InvalidArgument("apply_increment: state has " + std::to_string(s.D.size()) +
                          " triads for " + std::to_string(n) + " nodes");
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i * d);
    s.x[i] += du.segment<3>(k);
    if (d == 6) s.D[i] = (so3::exp_quat(du.segment<3>(k + 3)) * s.D[i]).normalized();
  }
}

}  // namespace sutura::engine
