#pragma once
// Zero-level-set extraction of a sampled field by marching tetrahedra.
#include <array>
#include <vector>

#include "triangle_soup.hpp"

namespace sutura::engine::anatomy {

/// Triangulates {f = 0} of `field` sampled at origin + h * (i, j, k) (node index
/// i + n0 * (j + n1 * k)). Each grid cube is split into the six tetrahedra around its main
/// diagonal (Kuhn/Freudenthal split, conforming between neighbouring cubes), so the result is a
/// closed, consistently oriented 2-manifold away from the grid border, with normals pointing
/// towards f > 0. Nodes with f = 0 count as outside. Vertices on a tetrahedron edge are shared
/// through the edge's node pair; their interpolation parameter is clamped to [0.02, 0.98] so no
/// two vertices coincide and no triangle is degenerate (the shape is poor: remesh afterwards).
/// Deterministic: vertices are numbered in traversal order. Cost O(nodes).
TriangleMesh marching_tetrahedra(const std::vector<double>& field, const Vec3& origin, double h,
                                 const std::array<int, 3>& n);

}  // namespace sutura::engine::anatomy
