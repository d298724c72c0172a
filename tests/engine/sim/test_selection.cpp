#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/sim/constraints.hpp"
#include "sutura/engine/sim/selection.hpp"

using namespace sutura::engine;

namespace {
std::vector<Vec3> grid() {
  std::vector<Vec3> p;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) p.emplace_back(i, j, 0.1 * i);
  return p;
}
}  // namespace

TEST(Selection, IdsNearestBoxPlane) {
  const auto p = grid();
  auto ids = select_vertices(p, SelectIds{{VertexId(5), VertexId(1), VertexId(5)}});
  ASSERT_EQ(ids.size(), 2u);  // sorted, duplicates removed
  EXPECT_EQ(ids[0].value, 1);
  EXPECT_EQ(ids[1].value, 5);
  auto near = select_vertices(p, SelectNearest{{Vec3(2.9, 1.1, 0.0)}});
  ASSERT_EQ(near.size(), 1u);
  EXPECT_EQ(near[0].value, 7);  // (3, 1)
  auto box = select_vertices(p, SelectBox{Vec3(-0.5, -0.5, -1), Vec3(1.5, 0.5, 1)});
  ASSERT_EQ(box.size(), 2u);
  EXPECT_EQ(box[1].value, 1);
  auto plane = select_vertices(p, SelectPlaneBand{Vec3(0, 2, 0), Vec3(0, 5, 0), 1e-9});
  ASSERT_EQ(plane.size(), 4u);
  EXPECT_EQ(plane[0].value, 8);
}

TEST(Selection, EmptyOrOutOfRangeIsAnError) {
  const auto p = grid();
  EXPECT_THROW(select_vertices(p, SelectIds{{VertexId(12)}}), InvalidArgument);
  EXPECT_THROW(select_vertices(p, SelectBox{Vec3(10, 10, 10), Vec3(11, 11, 11)}), InvalidArgument);
  EXPECT_THROW(select_vertices(p, SelectPlaneBand{Vec3(0, 0, 5), Vec3(0, 0, 1), 0.01}), InvalidArgument);
  EXPECT_THROW(select_vertices(p, SelectPlaneBand{Vec3(0, 0, 0), Vec3(0, 0, 0), 0.01}), InvalidArgument);
  EXPECT_THROW(select_vertices(p, SelectIds{}), InvalidArgument);
}

TEST(Constraints, ParseAndFix) {
  EXPECT_EQ(parse_dofs({"ux", "rz"}), kUx | kRz);
  EXPECT_EQ(parse_dofs({"all"}), kAllDofs);
  EXPECT_EQ(parse_dofs({"translations", "rx"}), kTranslations | kRx);
  EXPECT_THROW(parse_dofs({"uw"}), InvalidArgument);
  EXPECT_THROW(parse_dofs({}), InvalidArgument);
  Constraints c;
  c.fix({VertexId(2)}, kUy | kRx, 4);
  EXPECT_TRUE(c.is_fixed(2, 1));
  EXPECT_TRUE(c.is_fixed(2, 3));
  EXPECT_FALSE(c.is_fixed(2, 0));
  EXPECT_FALSE(c.is_fixed(1, 1));
  EXPECT_FALSE(c.is_fixed(99, 1));
  EXPECT_THROW(c.fix({VertexId(4)}, kUx, 4), InvalidArgument);
}
