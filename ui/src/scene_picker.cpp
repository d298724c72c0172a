#include "scene_picker.hpp"

#include <limits>

namespace sutura::ui {

void ScenePicker::rebuild(const std::vector<const engine::SurfaceMesh*>& meshes) {
  entries_.clear();
  entries_.reserve(meshes.size());
  for (const auto* m : meshes) {
    Entry e;
    e.mesh = m;
    e.bvh = engine::TriangleBvh(*m);
    e.loops = m->boundary_loops();
    e.reach = 3.0 * m->mean_edge_length();
    entries_.push_back(std::move(e));
  }
}

std::optional<Pick> ScenePicker::pick(const engine::Ray& ray) const {
  std::optional<Pick> best;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const auto hit = entries_[i].bvh.intersect(ray, 0.0, best ? best->hit.t : std::numeric_limits<double>::infinity());
    if (!hit) continue;
    Pick p;
    p.object = i;
    p.hit = *hit;
    const auto& mesh = *entries_[i].mesh;
    double nearest = std::numeric_limits<double>::infinity();
    for (auto v : mesh.face_vertices(hit->face)) {
      const double d = (mesh.position(v) - hit->point).squaredNorm();
      if (d < nearest) nearest = d, p.vertex = v;
    }
    double best_boundary = entries_[i].reach * entries_[i].reach;
    for (std::size_t l = 0; l < entries_[i].loops.size(); ++l)
      for (auto v : entries_[i].loops[l]) {
        const double d = (mesh.position(v) - hit->point).squaredNorm();
        if (d < best_boundary) {
          best_boundary = d;
          p.boundary_loop = static_cast<int>(l);
          p.boundary_vertex = v;
        }
      }
    best = p;
  }
  return best;
}

}  // namespace sutura::ui
