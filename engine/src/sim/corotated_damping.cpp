#include "corotated_damping.hpp"

#include "transpose_product.hpp"

namespace sutura::engine::detail {

CorotatedDamping::CorotatedDamping(const ShellSystem& sys, const DofMap& map)
    : rings_(*sys.problem.faces, sys.problem.num_nodes),
      dofs_per_node_(sys.dofs_per_node()),
      block_(sys.problem.num_nodes, -1) {
  const std::size_t d = dofs_per_node_;
  for (std::size_t i = 0; i < block_.size(); ++i) {
    const int first = map.full_to_free[i * d];
    bool all_free = first >= 0;
    for (std::size_t k = 1; k < d && all_free; ++k)
      all_free = map.full_to_free[i * d + k] == first + static_cast<int>(k);
    if (all_free) block_[i] = first;
  }
}

void CorotatedDamping::reset(const Eigen::SparseMatrix<double>& tangent,
                             const std::vector<Vec3>& x) {
  K_ = tangent;
  K_.makeCompressed();
  reference_ = x;
  restart_rotations();
}

void CorotatedDamping::restart_rotations() {
  // The rotations since the new reference start at the identity, which is also where the next
  // turn_to starts its Newton iteration from (NodalRotations::compute).
  Q_.assign(reference_.size(), Eigen::Matrix3d::Identity());
  turned_ = false;
}

double CorotatedDamping::turn_to(const std::vector<Vec3>& x) {
  if (empty()) return 0.0;
  const double bend = rings_.compute(reference_, x, Q_);
  turned_ = true;
  turned_to_ = x;
  return bend;
}

void CorotatedDamping::turn(bool transpose, Eigen::VectorXd& v) const {
  for (std::size_t i = 0; i < block_.size(); ++i) {
    const int f = block_[i];
    if (f < 0) continue;
    for (int b = 0; b < dofs_per_node_; b += 3) {
      const Vec3 u = v.segment<3>(f + b);
      v.segment<3>(f + b) = transpose ? Vec3(Q_[i].transpose() * u) : Vec3(Q_[i] * u);
    }
  }
}

void CorotatedDamping::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  if (!turned_) {
    transpose_product(K_, v, y);  // = K_d v: K_d is symmetric
    return;
  }
  scratch_ = v;
  turn(true, scratch_);
  transpose_product(K_, scratch_, y);
  turn(false, y);
}

const Eigen::SparseMatrix<double>& CorotatedDamping::matrix() {
  if (!turned_) return K_;
  std::vector<Eigen::Triplet<double>> blocks;
  blocks.reserve(static_cast<std::size_t>(K_.rows()) * 3);
  std::vector<bool> in_block(K_.rows(), false);
  for (std::size_t i = 0; i < block_.size(); ++i) {
    const int f = block_[i];
    if (f < 0) continue;
    for (int b = 0; b < dofs_per_node_; b += 3)
      for (int r = 0; r < 3; ++r) {
        in_block[f + b + r] = true;
        for (int c = 0; c < 3; ++c) blocks.emplace_back(f + b + r, f + b + c, Q_[i](r, c));
      }
  }
  for (Eigen::Index k = 0; k < K_.rows(); ++k)
    if (!in_block[k]) blocks.emplace_back(k, k, 1.0);
  Eigen::SparseMatrix<double> W(K_.rows(), K_.cols());
  W.setFromTriplets(blocks.begin(), blocks.end());
  const Eigen::SparseMatrix<double> WT = W.transpose();
  K_ = W * K_ * WT;
  K_.makeCompressed();
  reference_ = turned_to_;
  restart_rotations();
  return K_;
}

}  // namespace sutura::engine::detail
