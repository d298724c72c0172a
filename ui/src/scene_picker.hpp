#pragma once
// Picking: which object, face, point, vertex and boundary loop lie under a ray. One BVH per
// object (engine/geometry/bvh.hpp), rebuilt when the meshes change.
#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "sutura/engine/geometry/bvh.hpp"
#include "sutura/engine/mesh.hpp"
#include "sutura/render/scene.hpp"

namespace sutura::ui {

struct Pick {
  std::size_t object = 0;     ///< index into the meshes given to rebuild()
  engine::RayHit hit;
  engine::VertexId vertex;    ///< corner of the hit face nearest to the hit point
  /// The boundary vertex a click takes, with its loop index in SurfaceMesh::boundary_loops()
  /// order: a corner near the hit point (see pick()), else the nearest boundary vertex when
  /// it lies within 3 mean edge lengths of the hit point; -1 / invalid otherwise.
  int boundary_loop = -1;
  engine::VertexId boundary_vertex;
};

/// The part {t_min, t_max} of `ray` that `clip` leaves (render::ClipPlane: its normal's side
/// is cut away): all of it without a plane, t_min > t_max when nothing is left.
std::array<double, 2> uncut_part(const engine::Ray& ray, const std::optional<render::ClipPlane>& clip);

class ScenePicker {
 public:
  /// Rebuilds every BVH (O(F log F) in total). The meshes must outlive the next rebuild.
  void rebuild(const std::vector<const engine::SurfaceMesh*>& meshes);
  /// Nearest hit over all objects, or nullopt. `corner_snap` (radians, the angle a few
  /// pixels subtend; 0: off): a boundary corner (where the boundary turns by more than
  /// kCornerTurn: patch corners, incision ends) closer to the hit point than hit distance x
  /// tan(corner_snap) is taken in preference to a nearer boundary vertex, so that clicking
  /// near a corner picks it at any mesh density. Only hits with t in [t_min, t_max] count (the
  /// part of the ray a clip plane leaves). O(log F + boundary vertices).
  [[nodiscard]] std::optional<Pick> pick(const engine::Ray& ray, double corner_snap = 0.0,
                                         double t_min = 0.0,
                                         double t_max = std::numeric_limits<double>::infinity()) const;

  static constexpr double kCornerTurnDeg = 60.0;

 private:
  struct Entry {
    const engine::SurfaceMesh* mesh = nullptr;
    engine::TriangleBvh bvh;
    std::vector<std::vector<engine::VertexId>> loops;
    std::vector<std::pair<int, engine::VertexId>> corners;  ///< (loop, vertex)
    double reach = 0.0;  ///< boundary snapping distance, mm
  };
  std::vector<Entry> entries_;
};

}  // namespace sutura::ui
