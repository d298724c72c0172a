#include "lbfgs.hpp"

#include <cmath>

namespace sutura::engine::detail {

bool LbfgsHistory::add(const Eigen::VectorXd& s, const Eigen::VectorXd& y) {
  const double sy = s.dot(y);
  if (!std::isfinite(sy) || !(sy > 1e-10 * s.norm() * y.norm())) return false;
  if (static_cast<int>(pairs_.size()) == depth_) pairs_.pop_front();
  pairs_.push_back({s, y, 1.0 / sy});
  return true;
}

}  // namespace sutura::engine::detail
