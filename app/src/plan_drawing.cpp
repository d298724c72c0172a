#include "sutura/app/plan_drawing.hpp"

namespace sutura::app {

namespace {

std::vector<render::Point3> polyline(const engine::SurfaceMesh& mesh, const std::vector<engine::VertexId>& chain) {
  std::vector<render::Point3> pts;
  pts.reserve(chain.size());
  for (const auto v : chain) {
    if (v.index() >= mesh.num_vertices()) continue;
    const auto& p = mesh.position(v);
    pts.push_back({float(p.x()), float(p.y()), float(p.z())});
  }
  return pts;
}

}  // namespace

PlanDrawing plan_drawing(const SceneObject& obj, const engine::SurfaceMesh& state, bool marks) {
  PlanDrawing d;
  const bool current = &state == &obj.mesh;
  const std::vector<std::uint32_t> all = state.flat_triangles();
  const auto& material = obj.sim.face_material;
  if (!current || material.size() != state.num_faces()) {
    d.wall_triangles = all;
  } else {
    for (std::size_t f = 0; f < state.num_faces(); ++f) {
      auto& out = material[f] == 0 ? d.wall_triangles : d.patch_triangles;
      out.insert(out.end(), all.begin() + std::ptrdiff_t(3 * f), all.begin() + std::ptrdiff_t(3 * f + 3));
    }
  }
  if (current && marks) {
    for (const auto& c : obj.sim.marks.incisions) d.incisions.push_back(polyline(state, c));
    for (const auto& c : obj.sim.marks.sutures) d.sutures.push_back(polyline(state, c));
  }
  return d;
}

void add_plan_surfaces(render::Scene& scene, std::span<const float> positions, std::span<const float> scalars,
                       const PlanDrawing& d, render::Color wall, bool wireframe) {
  for (const auto* triangles : {&d.wall_triangles, &d.patch_triangles}) {
    if (triangles->empty()) continue;
    render::SurfaceItem s;
    s.positions = positions;
    s.triangles = *triangles;
    s.scalars = scalars;
    s.color = triangles == &d.wall_triangles ? wall : kPatchColor;
    s.wireframe = wireframe;
    scene.surfaces.push_back(s);
  }
}

void add_plan_lines(render::Scene& scene, const PlanDrawing& d) {
  for (const auto* set : {&d.incisions, &d.sutures})
    for (const auto& pts : *set) {
      if (pts.size() < 2) continue;
      render::PolylineItem line;
      line.points = pts;
      line.color = set == &d.incisions ? kIncisionColor : kSutureColor;
      line.width_px = 3.0f;
      scene.polylines.push_back(std::move(line));
    }
}

}  // namespace sutura::app
