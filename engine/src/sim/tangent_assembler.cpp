#include "sutura/engine/sim/tangent_assembler.hpp"

#include <algorithm>

namespace sutura::engine {

namespace {
std::uint64_t key(const Eigen::Triplet<double>& t) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(t.row())) << 32) |
         static_cast<std::uint32_t>(t.col());
}
}  // namespace

void TangentAssembler::build(const Triplets& K, const std::vector<int>& full_to_free,
                             Eigen::Index num_free) {
  full_to_free_ = full_to_free;
  keys_.resize(K.size());
  slot_.assign(K.size(), -1);
  std::vector<Eigen::Triplet<double>> kept;
  kept.reserve(K.size());
  for (std::size_t i = 0; i < K.size(); ++i) {
    keys_[i] = key(K[i]);
    const int r = full_to_free[K[i].row()], c = full_to_free[K[i].col()];
    if (r >= 0 && c >= 0) kept.emplace_back(r, c, 1.0);
  }
  pattern_.resize(num_free, num_free);
  pattern_.setFromTriplets(kept.begin(), kept.end());
  pattern_.makeCompressed();
  const auto* outer = pattern_.outerIndexPtr();
  const auto* inner = pattern_.innerIndexPtr();
  for (std::size_t i = 0; i < K.size(); ++i) {
    const int r = full_to_free[K[i].row()], c = full_to_free[K[i].col()];
    if (r < 0 || c < 0) continue;
    const auto* begin = inner + outer[c];
    const auto* end = inner + outer[c + 1];
    slot_[i] = std::lower_bound(begin, end, r) - inner;  // column-major: inner = row
  }
}

void TangentAssembler::assemble(const Triplets& K, const std::vector<int>& full_to_free,
                                Eigen::Index num_free, Eigen::SparseMatrix<double>& out) {
  bool same = K.size() == keys_.size() && full_to_free == full_to_free_ &&
              pattern_.rows() == num_free;
  for (std::size_t i = 0; same && i < K.size(); ++i) same = keys_[i] == key(K[i]);
  if (!same) build(K, full_to_free, num_free);
  out = pattern_;
  double* values = out.valuePtr();
  std::fill(values, values + out.nonZeros(), 0.0);
  for (std::size_t i = 0; i < K.size(); ++i)
    if (slot_[i] >= 0) values[slot_[i]] += K[i].value();
}

}  // namespace sutura::engine
