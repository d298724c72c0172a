#pragma once
// The supernodal elimination tree of a CHOLMOD factor split into two independent halves and a
// top (private to engine/src/sim), so that a factorisation or a triangular solve can work on
// the halves at the same time on two threads.
//
// The parent of a supernode is the supernode holding its first off-diagonal row; all its
// off-diagonal rows belong to ancestors. The halves are unions of disjoint subtrees (closed
// under descendants) with about equal numbers of factor entries; the top is everything else
// (the ancestors of both: with a nested-dissection ordering, the top separators). Hence a
// half's supernode touches rows of its own half or of the top, never of the other half.
// Found from the roots: the heaviest subtree of the frontier is moved to the top, its children
// taking its place, until the frontier's subtrees fall into two halves of about equal weight
// (largest first, each into the lighter half). Depends on the factor's structure only.
#include <array>
#include <cstdint>
#include <vector>

#include <cholmod.h>

namespace sutura::engine::detail {

/// The supernodal structure of a CHOLMOD factor with int indices (the engine's interface), read
/// through typed pointers. Supernode s holds columns super[s] .. super[s + 1] - 1; its rows are
/// rows[row_start[s]] .. rows[row_start[s + 1] - 1] (its own columns first); its values, an
/// nrow x ncol column-major block, start at value_start[s] in L.x.
struct SupernodalArrays {
  explicit SupernodalArrays(const cholmod_factor& L)
      : super(static_cast<const int*>(L.super)),
        row_start(static_cast<const int*>(L.pi)),
        value_start(static_cast<const int*>(L.px)),
        rows(static_cast<const int*>(L.s)) {}
  [[nodiscard]] int ncol(int s) const { return super[s + 1] - super[s]; }
  [[nodiscard]] int nrow(int s) const { return row_start[s + 1] - row_start[s]; }
  [[nodiscard]] std::int64_t block_size(int s) const {
    return static_cast<std::int64_t>(nrow(s)) * ncol(s);
  }

  const int* super;
  const int* row_start;
  const int* value_start;
  const int* rows;
};

struct SupernodeSplit {
  /// The supernodes of each half and of the top, each list in increasing order (descendants
  /// before ancestors).
  std::array<std::vector<int>, 2> halves;
  std::vector<int> top;
  std::vector<int> column_super;          ///< per column of L: the supernode holding it
  std::vector<std::uint8_t> is_top_column;  ///< per column of L: 1 if its supernode is top
  std::vector<int> top_columns;             ///< the top supernodes' columns, increasing
};

/// Splits `L`'s supernodal tree (L: supernodal, int indices; the symbolic structure suffices, so
/// it is computed once per analysis). Cost O(n + nnz(L.s) + nsuper log).
/// Should the supernodes not be numbered descendants first (CHOLMOD's always are), everything
/// is top.
SupernodeSplit split_supernode_tree(const cholmod_factor& L);

}  // namespace sutura::engine::detail
