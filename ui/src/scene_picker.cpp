#include "scene_picker.hpp"

#include <cmath>
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
    const double cos_turn = std::cos(kCornerTurnDeg * M_PI / 180.0);
    for (std::size_t l = 0; l < e.loops.size(); ++l) {
      const auto& loop = e.loops[l];
      const std::size_t n = loop.size();
      for (std::size_t i = 0; i < n && n >= 3; ++i) {
        const engine::Vec3 in = m->position(loop[i]) - m->position(loop[(i + n - 1) % n]);
        const engine::Vec3 out = m->position(loop[(i + 1) % n]) - m->position(loop[i]);
        const double norms = in.norm() * out.norm();
        if (norms > 0.0 && in.dot(out) < cos_turn * norms) e.corners.emplace_back(int(l), loop[i]);
      }
    }
    e.reach = 3.0 * m->mean_edge_length();
    entries_.push_back(std::move(e));
  }
}

std::array<double, 2> uncut_part(const engine::Ray& ray, const std::optional<render::ClipPlane>& clip) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (!clip) return {0.0, kInf};
  const engine::Vec3 n(clip->normal[0], clip->normal[1], clip->normal[2]);
  const engine::Vec3 p(clip->point[0], clip->point[1], clip->point[2]);
  const double side = n.dot(ray.origin - p);  // > 0: the origin is cut away
  const double along = n.dot(ray.direction);
  if (side > 0.0) return along < 0.0 ? std::array<double, 2>{-side / along, kInf} : std::array<double, 2>{kInf, 0.0};
  return along > 0.0 ? std::array<double, 2>{0.0, -side / along} : std::array<double, 2>{0.0, kInf};
}

std::optional<Pick> ScenePicker::pick(const engine::Ray& ray, double corner_snap, double t_min,
                                      double t_max) const {
  std::optional<Pick> best;
  if (!(t_min <= t_max)) return best;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    const auto hit = entries_[i].bvh.intersect(ray, t_min, best ? best->hit.t : t_max);
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
    double best_corner = std::pow(hit->t * std::tan(corner_snap), 2);
    for (const auto& [l, v] : entries_[i].corners) {
      const double d = (mesh.position(v) - hit->point).squaredNorm();
      if (d < best_corner) {
        best_corner = d;
        p.boundary_loop = l;
        p.boundary_vertex = v;
      }
    }
    best = p;
  }
  return best;
}

}  // namespace sutura::ui
