// boundary_chain: runs of boundary vertices (what a suture joins), named by vertices or by
// points near their ends.
#include "sutura/engine/surgery/boundary_chain.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/generators.hpp"

namespace sutura::engine {
namespace {

constexpr int kAround = 24;
constexpr double kRadius = 4.0;

SurfaceMesh tube() {
  TubeParams p;
  p.radius = kRadius;
  p.length = 20.0;
  p.segments_around = kAround;
  p.segments_along = 10;
  return make_tube(p);
}

double chord() { return 2.0 * kRadius * std::sin(std::numbers::pi / kAround); }

bool boundary_edge(const SurfaceMesh& m, VertexId a, VertexId b) {
  const auto loops = m.boundary_loops();
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i)
      if (loop[i] == a && loop[(i + 1) % loop.size()] == b) return true;
  return false;
}

TEST(BoundaryChain, FollowsTheBoundaryDirectionBetweenItsEnds) {
  const SurfaceMesh m = tube();
  const auto loop = m.boundary_loops().at(0);
  ASSERT_EQ(loop.size(), std::size_t(kAround));
  const BoundaryChain c = boundary_chain(m, loop[3], loop[9]);
  EXPECT_FALSE(c.closed);
  ASSERT_EQ(c.vertices.size(), 7u);
  EXPECT_EQ(c.vertices.front(), loop[3]);
  EXPECT_EQ(c.vertices.back(), loop[9]);
  for (std::size_t i = 0; i + 1 < c.vertices.size(); ++i)
    EXPECT_TRUE(boundary_edge(m, c.vertices[i], c.vertices[i + 1])) << i;  // mesh on the left
  EXPECT_NEAR(chain_length(m, c), 6 * chord(), 1e-9);
  // The other way round runs the long way, across the loop's start.
  const BoundaryChain back = boundary_chain(m, loop[9], loop[3]);
  EXPECT_EQ(back.vertices.size(), std::size_t(kAround - 6 + 1));
  EXPECT_NEAR(chain_length(m, back), (kAround - 6) * chord(), 1e-9);
}

TEST(BoundaryChain, TheSameVertexTwiceIsTheWholeLoopStartingThere) {
  const SurfaceMesh m = tube();
  const auto loop = m.boundary_loops().at(1);
  const BoundaryChain c = boundary_chain(m, loop[5], loop[5]);
  EXPECT_TRUE(c.closed);
  ASSERT_EQ(c.vertices.size(), std::size_t(kAround));
  EXPECT_EQ(c.vertices.front(), loop[5]);
  EXPECT_NEAR(chain_length(m, c), kAround * chord(), 1e-9);  // the closing edge counts
}

TEST(BoundaryChain, VerticesOffTheBoundaryOrOnTwoLoopsAreRefused) {
  const SurfaceMesh m = tube();
  const auto loops = m.boundary_loops();
  VertexId inner;
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    if (!m.is_boundary(VertexId(int(v)))) {
      inner = VertexId(int(v));
      break;
    }
  ASSERT_TRUE(inner.valid());
  EXPECT_THROW(boundary_chain(m, inner, loops[0][0]), InvalidArgument);
  EXPECT_THROW(boundary_chain(m, loops[0][0], loops[1][0]), InvalidArgument);
}

TEST(BoundaryChain, PointsNearTheEndsNameTheChain) {
  const SurfaceMesh m = tube();
  const auto loop = m.boundary_loops().at(0);
  const Vec3 off(0.1, 0.0, 0.0);
  ChainSpec spec;
  spec.from = m.position(loop[2]) + off;
  spec.to = m.position(loop[6]) - off;
  const BoundaryChain c = find_boundary_chain(m, spec);
  ASSERT_EQ(c.vertices.size(), 5u);
  EXPECT_EQ(c.vertices.front(), loop[2]);
  EXPECT_EQ(c.vertices.back(), loop[6]);

  ChainSpec whole;
  whole.from = m.position(loop[4]);
  whole.loop = true;
  const BoundaryChain l = find_boundary_chain(m, whole);
  EXPECT_TRUE(l.closed);
  EXPECT_EQ(l.vertices.front(), loop[4]);
  EXPECT_EQ(l.vertices.size(), std::size_t(kAround));

  ChainSpec far = spec;
  far.from = m.position(loop[2]) + Vec3(0.0, 0.0, -5.0);  // 5 mm beyond the end
  try {
    (void)find_boundary_chain(m, far);
    ADD_FAILURE() << "a point 5 mm from the boundary named a chain";
  } catch (const InvalidArgument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("chain point 'from'"), std::string::npos) << m;
    EXPECT_NE(m.find("mm from the nearest boundary vertex (limit 1.0"), std::string::npos) << m;
  }
  ChainSpec same = spec;
  same.to = spec.from;
  EXPECT_THROW((void)find_boundary_chain(m, same), InvalidArgument);  // needs loop: true
  ChainSpec across = spec;
  across.to = m.position(m.boundary_loops().at(1)[0]);
  EXPECT_THROW((void)find_boundary_chain(m, across), InvalidArgument);
}

}  // namespace
}  // namespace sutura::engine
