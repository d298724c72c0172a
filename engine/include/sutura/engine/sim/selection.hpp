#pragma once
// Vertex selections for constraints and loads: explicit ids, the vertex nearest to a point,
// an axis-aligned box, or a distance band around a plane.
#include <optional>
#include <variant>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct SelectIds {
  std::vector<VertexId> ids;
};
/// The single vertex nearest to each point (ties: lowest id).
struct SelectNearest {
  std::vector<Vec3> points;
};
/// Vertices with min <= p <= max componentwise (mm).
struct SelectBox {
  Vec3 min, max;
};
/// Vertices with |(p - point) . n| <= distance, n = normalised `normal` (mm).
struct SelectPlaneBand {
  Vec3 point, normal;
  double distance = 1e-6;
};
using Selection = std::variant<SelectIds, SelectNearest, SelectBox, SelectPlaneBand>;

/// Sorted, duplicate-free vertex ids matched by `sel` on `positions`. Throws InvalidArgument
/// when nothing matches or an id is out of range (the message says which selection). O(V).
std::vector<VertexId> select_vertices(const std::vector<Vec3>& positions, const Selection& sel);

}  // namespace sutura::engine
