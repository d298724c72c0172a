#pragma once
// Fast repeated assembly of the free-DOF tangent from element triplets.
//
// Why: the shell models emit a fixed list of triplets for a given topology (6.5 million at
// 20k elements); Eigen's setFromTriplets sorts them on every call, which costs more than
// computing them. The first call records, for every entry of the compressed matrix, which
// triplets add up to it; later calls with the same triplet structure only gather values.
// Each entry is summed by one thread, in triplet order, so the result is deterministic and
// independent of the thread count (and bit-identical to a serial scatter in triplet order).
// The structure is re-checked on every call (one parallel pass over the row/column pairs)
// and rebuilt when it changed.
#include <cstdint>
#include <vector>

#include <Eigen/Sparse>

#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine {

class TangentAssembler {
 public:
  /// Assembles `K` (full DOF numbering) into `out` (free x free), dropping entries whose row
  /// or column is not free (full_to_free[i] < 0). Duplicates are summed.
  void assemble(const Triplets& K, const std::vector<int>& full_to_free, Eigen::Index num_free,
                Eigen::SparseMatrix<double>& out);

  /// Reusable triplet buffer for the model (keeps its capacity between calls).
  Triplets& buffer() { return buffer_; }

 private:
  void build(const Triplets& K, const std::vector<int>& full_to_free, Eigen::Index num_free);

  Triplets buffer_;
  std::vector<std::uint64_t> keys_;  // (row << 32 | col) of each triplet, full numbering
  // Entry e of the compressed matrix is the sum of the values of the triplets
  // sources_[first_[e]], ..., sources_[first_[e + 1] - 1], in increasing triplet order
  // (triplets on a fixed row or column are in none).
  std::vector<std::int64_t> first_;
  std::vector<std::uint32_t> sources_;
  std::vector<int> full_to_free_;
  // The compressed column-major pattern of the free x free matrix (outer/inner indices).
  Eigen::Index num_free_ = -1;
  std::vector<int> outer_, inner_;
};

}  // namespace sutura::engine
