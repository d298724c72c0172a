#include "supernode_tree.hpp"

#include <algorithm>
#include <utility>

namespace sutura::engine::detail {

namespace {

// The split stops when the heavier half holds at most this share of the halves' entries.
constexpr double kBalance = 0.55;
// At most this many supernodes are moved from the halves to the top while balancing.
constexpr int kMaxTopSupernodes = 1000;

}  // namespace

SupernodeSplit split_supernode_tree(const cholmod_factor& L) {
  SupernodeSplit out;
  const auto n = static_cast<int>(L.n);
  const auto nsuper = static_cast<int>(L.nsuper);
  const SupernodalArrays a(L);
  const int* super = a.super;
  const int* row_start = a.row_start;
  const int* rows = a.rows;
  std::vector<int> column_super(static_cast<std::size_t>(n));
  for (int s = 0; s < nsuper; ++s)
    for (int k = super[s]; k < super[s + 1]; ++k) column_super[k] = s;
  std::vector<int> parent(static_cast<std::size_t>(nsuper), -1);
  std::vector<double> weight(static_cast<std::size_t>(nsuper), 0.0);  // entries in the subtree
  std::vector<int> child_count(static_cast<std::size_t>(nsuper) + 1, 0);
  bool postordered = true;
  for (int s = 0; s < nsuper; ++s) {
    const int ncol = a.ncol(s);
    weight[s] += static_cast<double>(a.block_size(s));
    if (a.nrow(s) > ncol) {
      const int* first = rows + row_start[s] + ncol;
      parent[s] = column_super[*std::min_element(first, rows + row_start[s + 1])];
      if (parent[s] <= s) postordered = false;
    }
  }
  // Ancestors after descendants is what the solves' order relies on; CHOLMOD's supernodes are
  // always so numbered. Should a factor not be, everything is top: one thread, CHOLMOD's order.
  if (!postordered) {
    for (int s = 0; s < nsuper; ++s) out.top.push_back(s);
  } else {
    for (int s = 0; s < nsuper; ++s)
      if (parent[s] >= 0) weight[parent[s]] += weight[s], ++child_count[parent[s] + 1];
    for (int s = 0; s < nsuper; ++s) child_count[s + 1] += child_count[s];
    std::vector<int> children(static_cast<std::size_t>(child_count[nsuper]));
    {
      std::vector<int> next(child_count.begin(), child_count.end() - 1);
      for (int s = 0; s < nsuper; ++s)
        if (parent[s] >= 0) children[next[parent[s]]++] = s;
    }
    constexpr int kTop = -1;
    std::vector<int> group(static_cast<std::size_t>(nsuper), -2);  // -2: inherits its parent's
    std::vector<int> frontier;
    for (int s = 0; s < nsuper; ++s)
      if (parent[s] < 0) frontier.push_back(s);
    const auto heavier_first = [&](int a, int b) {
      return weight[a] != weight[b] ? weight[a] > weight[b] : a < b;
    };
    std::vector<int> bin_of;
    for (int moved = 0;; ++moved) {
      std::sort(frontier.begin(), frontier.end(), heavier_first);
      double bins[2] = {0.0, 0.0};
      bin_of.assign(frontier.size(), 0);
      for (std::size_t i = 0; i < frontier.size(); ++i) {
        const int b = bins[1] < bins[0] ? 1 : 0;
        bin_of[i] = b;
        bins[b] += weight[frontier[i]];
      }
      const double total = bins[0] + bins[1];
      const int heaviest = frontier.empty() ? -1 : frontier.front();
      if (total == 0.0 || std::max(bins[0], bins[1]) <= kBalance * total ||
          moved == kMaxTopSupernodes || child_count[heaviest] == child_count[heaviest + 1])
        break;
      group[heaviest] = kTop;
      frontier.erase(frontier.begin());
      frontier.insert(frontier.end(), children.begin() + child_count[heaviest],
                      children.begin() + child_count[heaviest + 1]);
    }
    for (std::size_t i = 0; i < frontier.size(); ++i) group[frontier[i]] = bin_of[i];
    for (int s = nsuper - 1; s >= 0; --s)
      if (group[s] == -2) group[s] = parent[s] >= 0 ? group[parent[s]] : kTop;
    for (int s = 0; s < nsuper; ++s)
      (group[s] == kTop ? out.top : out.halves[group[s]]).push_back(s);
  }
  out.is_top_column.assign(static_cast<std::size_t>(n), 0);
  for (const int s : out.top)
    for (int k = super[s]; k < super[s + 1]; ++k)
      out.is_top_column[k] = 1, out.top_columns.push_back(k);
  out.column_super = std::move(column_super);
  return out;
}

}  // namespace sutura::engine::detail
