// The split of a supernodal elimination tree into two independent halves and a top
// (supernode_tree.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "cholmod_fixture.hpp"
#include "supernode_tree.hpp"

namespace sutura::engine {
namespace {

// Every supernode is in exactly one list; the rows a half's supernode updates belong to that
// half or to the top (so the halves can be worked on at the same time); the top's rows are all
// top rows; the halves carry about equal weight and the top is small.
TEST(SupernodeTree, SplitsIntoTwoIndependentBalancedHalvesAndASmallTop) {
  testing::SupernodalLlt llt;
  llt.compute(testing::grid_laplacian(120));
  ASSERT_EQ(llt.info(), Eigen::Success);
  const cholmod_factor& L = llt.factor();
  const detail::SupernodeSplit split = detail::split_supernode_tree(L);
  const detail::SupernodalArrays a(L);
  const int* super = a.super;
  const int* row_start = a.row_start;
  const int* rows = a.rows;
  const auto nsuper = static_cast<int>(L.nsuper);
  std::vector<int> group(static_cast<std::size_t>(nsuper), -2), column_group(L.n, -2);
  const auto put = [&](int s, int g) {
    ASSERT_EQ(group[s], -2) << "supernode " << s << " listed twice";
    group[s] = g;
    for (int k = super[s]; k < super[s + 1]; ++k) column_group[k] = g;
  };
  for (int h = 0; h < 2; ++h) {
    EXPECT_TRUE(std::is_sorted(split.halves[h].begin(), split.halves[h].end()));
    for (const int s : split.halves[h]) put(s, h);
  }
  for (const int s : split.top) put(s, -1);
  ASSERT_TRUE(std::none_of(group.begin(), group.end(), [](int g) { return g == -2; }));
  double weight[2] = {0.0, 0.0};
  for (int s = 0; s < nsuper; ++s) {
    const int ncol = super[s + 1] - super[s], nrow = row_start[s + 1] - row_start[s];
    if (group[s] >= 0) weight[group[s]] += static_cast<double>(nrow) * ncol;
    for (int k = super[s]; k < super[s + 1]; ++k) {
      EXPECT_EQ(split.column_super[k], s);
      EXPECT_EQ(split.is_top_column[k], group[s] == -1 ? 1 : 0);
    }
    for (int p = row_start[s] + ncol; p < row_start[s + 1]; ++p) {
      const int g = column_group[rows[p]];
      if (group[s] >= 0) EXPECT_TRUE(g == group[s] || g == -1) << "supernode " << s;
      else EXPECT_EQ(g, -1) << "top supernode " << s << " updates a half";
    }
  }
  EXPECT_GT(weight[0], 0.0);
  EXPECT_GT(weight[1], 0.0);
  EXPECT_LE(std::max(weight[0], weight[1]), 0.55 * (weight[0] + weight[1]));
  EXPECT_LT(split.top.size(), static_cast<std::size_t>(nsuper) / 10);
}

}  // namespace
}  // namespace sutura::engine
