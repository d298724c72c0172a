#include "sutura/app/element_check.hpp"

#include <algorithm>
#include <cstdio>

#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::app {

namespace {

std::string where_text(const ThinElements& t) {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%zu rest triangle%s of '%s' (smallest angle %.2f degrees, near (%.1f, %.1f, %.1f) mm)",
                t.count, t.count == 1 ? "" : "s", t.object.c_str(), t.smallest_deg, t.where.front().x(),
                t.where.front().y(), t.where.front().z());
  return buf;
}

std::string list(const std::vector<ThinElements>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? "; " : "") + where_text(v[i]);
  return out;
}

}  // namespace

std::optional<std::string> ElementCheck::refusal() const {
  if (refused.empty()) return std::nullopt;
  return "Too thin to relax: " + list(refused) +
         ". A run cannot stretch triangles this thin and fails. They come from edits made "
         "without remeshing (an older session, or \"remesh\": false): undo those edits and redo "
         "them in this window, which remeshes around every cut and seam. The red dots mark them.";
}

std::optional<std::string> ElementCheck::warning() const {
  if (warned.empty()) return std::nullopt;
  return "Thin elements: " + list(warned) + ". The run may fail to relax them (orange dots).";
}

ElementCheck check_elements(const Workspace& workspace) {
  ElementCheck check;
  for (const SceneObject& o : workspace.objects()) {
    ThinElements refused, warned;
    refused.object = warned.object = o.name;
    refused.smallest_deg = warned.smallest_deg = 180.0;
    const auto& rest = o.sim.rest.elements;
    const std::size_t faces = std::min(rest.size(), o.mesh.num_faces());
    for (std::size_t f = 0; f < faces; ++f) {
      const auto& X = rest[f].X;
      const double angle = engine::smallest_angle_deg(X[0], X[1], X[2]);
      ThinElements* t = angle < ElementCheck::kRefuseDeg ? &refused
                        : angle < ElementCheck::kWarnDeg  ? &warned
                                                          : nullptr;
      if (!t) continue;
      ++t->count;
      const auto v = o.mesh.face_vertices(engine::FaceId(int(f)));
      const engine::Vec3 c = (o.mesh.position(v[0]) + o.mesh.position(v[1]) + o.mesh.position(v[2])) / 3.0;
      // The smallest first, so that the text names it.
      if (angle < t->smallest_deg) {
        t->smallest_deg = angle;
        t->where.insert(t->where.begin(), c);
      } else {
        t->where.push_back(c);
      }
      if (t->where.size() > ElementCheck::kMaxMarkers) t->where.pop_back();
    }
    if (refused.count) check.refused.push_back(std::move(refused));
    if (warned.count) check.warned.push_back(std::move(warned));
  }
  return check;
}

std::vector<SmallestAngle> smallest_angles(const Workspace& workspace) {
  std::vector<SmallestAngle> out;
  for (const SceneObject& o : workspace.objects()) {
    if (o.mesh.num_faces() == 0) continue;
    const engine::MeshQuality q = engine::mesh_quality(o.mesh);
    SmallestAngle a{o.name, q.min_angle_deg, engine::Vec3::Zero(), 0.0};
    const auto v = o.mesh.face_vertices(q.worst_face);
    a.where = (o.mesh.position(v[0]) + o.mesh.position(v[1]) + o.mesh.position(v[2])) / 3.0;
    if (std::size_t(q.worst_face.index()) < o.sim.rest.elements.size()) {
      const auto& X = o.sim.rest.elements[std::size_t(q.worst_face.index())].X;
      a.rest_degrees = engine::smallest_angle_deg(X[0], X[1], X[2]);
    }
    out.push_back(a);
  }
  return out;
}

std::optional<SmallestAngle> worst_angle(const std::vector<SmallestAngle>& angles) {
  const auto worst = std::min_element(angles.begin(), angles.end(),
                                      [](const auto& a, const auto& b) { return a.degrees < b.degrees; });
  if (worst == angles.end()) return std::nullopt;
  return *worst;
}

}  // namespace sutura::app
