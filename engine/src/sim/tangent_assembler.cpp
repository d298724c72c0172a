#include "sutura/engine/sim/tangent_assembler.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {
std::uint64_t key(const Eigen::Triplet<double>& t) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(t.row())) << 32) |
         static_cast<std::uint32_t>(t.col());
}

// Below this many triplets the threads cost more than they save (about 30 elements).
constexpr std::size_t kParallelTriplets = 10000;
}  // namespace

void TangentAssembler::build(const Triplets& K, const std::vector<int>& full_to_free,
                             Eigen::Index num_free) {
  if (K.size() > std::numeric_limits<std::uint32_t>::max())
    throw InvalidArgument("tangent assembly: more than 2^32 triplets");
  full_to_free_ = full_to_free;
  keys_.resize(K.size());
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
  // The entry of every kept triplet, then a counting sort by entry (stable: triplet order).
  std::vector<std::int64_t> entry(K.size(), -1);
  first_.assign(static_cast<std::size_t>(pattern_.nonZeros()) + 1, 0);
  for (std::size_t i = 0; i < K.size(); ++i) {
    const int r = full_to_free[K[i].row()], c = full_to_free[K[i].col()];
    if (r < 0 || c < 0) continue;
    const auto* begin = inner + outer[c];
    const auto* end = inner + outer[c + 1];
    entry[i] = std::lower_bound(begin, end, r) - inner;  // column-major: inner = row
    ++first_[static_cast<std::size_t>(entry[i]) + 1];
  }
  for (std::size_t e = 1; e < first_.size(); ++e) first_[e] += first_[e - 1];
  sources_.resize(static_cast<std::size_t>(first_.back()));
  std::vector<std::int64_t> next(first_.begin(), first_.end() - 1);
  for (std::size_t i = 0; i < K.size(); ++i)
    if (entry[i] >= 0) sources_[static_cast<std::size_t>(next[entry[i]]++)] = static_cast<std::uint32_t>(i);
}

void TangentAssembler::assemble(const Triplets& K, const std::vector<int>& full_to_free,
                                Eigen::Index num_free, Eigen::SparseMatrix<double>& out) {
  bool same = K.size() == keys_.size() && full_to_free == full_to_free_ &&
              pattern_.rows() == num_free;
  const auto n = static_cast<std::ptrdiff_t>(K.size());
  const bool parallel = K.size() >= kParallelTriplets;
  if (same) {
    std::ptrdiff_t changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed) if (parallel)
    for (std::ptrdiff_t i = 0; i < n; ++i) changed += keys_[i] != key(K[i]) ? 1 : 0;
    same = changed == 0;
  }
  if (!same) build(K, full_to_free, num_free);
  out = pattern_;
  double* values = out.valuePtr();
  const auto entries = static_cast<std::ptrdiff_t>(out.nonZeros());
#pragma omp parallel for schedule(static) if (parallel)
  for (std::ptrdiff_t e = 0; e < entries; ++e) {
    double sum = 0.0;
    for (std::int64_t k = first_[e]; k < first_[e + 1]; ++k) sum += K[sources_[k]].value();
    values[e] = sum;
  }
}

}  // namespace sutura::engine
