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

struct SupernodeSplit {
  /// The supernodes of each half and of the top, each list in increasing order (descendants
  /// before ancestors).
  std::array<std::vector<int>, 2> halves;
  std::vector<int> top;
  std::vector<int> column_super;          ///< per column of L: the supernode holding it
  std::vector<std::uint8_t> is_top_column;  ///< per column of L: 1 if its supernode is top
};

/// Splits `L`'s supernodal tree (L: supernodal, int indices). Cost O(n + nnz(L.s) + nsuper log).
/// Should the supernodes not be numbered descendants first (CHOLMOD's always are), everything
/// is top.
SupernodeSplit split_supernode_tree(const cholmod_factor& L);

}  // namespace sutura::engine::detail
