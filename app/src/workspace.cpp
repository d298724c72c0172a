#include "sutura/app/workspace.hpp"

#include <algorithm>
#include <stdexcept>

namespace sutura::app {

SceneObject& Workspace::add(std::string name, engine::SurfaceMesh mesh) {
  if (find(name) != nullptr)
    throw std::invalid_argument("an object named '" + name + "' already exists");
  auto obj = std::make_shared<SceneObject>();
  obj->name = std::move(name);
  obj->before = mesh;
  obj->sim = engine::attributes_at_rest(mesh);
  obj->mesh = std::move(mesh);
  objects_.push_back(std::move(obj));
  return *objects_.back();
}

SceneObject* Workspace::edit(const std::string& name) {
  for (auto& o : objects_)
    if (o->name == name) {
      if (o.use_count() > 1) o = std::make_shared<SceneObject>(*o);
      return o.get();
    }
  return nullptr;
}

const SceneObject* Workspace::find(const std::string& name) const {
  for (const auto& o : objects_)
    if (o->name == name) return o.get();
  return nullptr;
}

std::string Workspace::names() const {
  std::string s;
  for (const auto& o : objects_) s += (s.empty() ? "" : ", ") + o->name;
  return s.empty() ? "(none)" : s;
}

bool has_pending_relaxation(const SceneObject& obj) { return obj.sim.relax_from.has_value(); }

bool has_reference_positions(const SceneObject& obj) {
  return obj.sim.reference.size() == obj.mesh.num_vertices();
}

std::vector<MaterialRegion> material_regions(const SceneObject& obj) {
  std::vector<MaterialRegion> regions;
  for (const engine::ShellMaterial& m : obj.sim.materials) regions.push_back({m, 0});
  for (const int k : obj.sim.face_material)
    if (k >= 0 && std::size_t(k) < regions.size()) ++regions[std::size_t(k)].faces;
  return regions;
}

engine::Vec3 loop_centroid(const engine::SurfaceMesh& mesh, const std::vector<engine::VertexId>& loop) {
  engine::Vec3 c = engine::Vec3::Zero();
  for (const auto v : loop) c += mesh.position(v);
  return loop.empty() ? c : engine::Vec3(c / static_cast<double>(loop.size()));
}

std::string end_name(const SceneObject& obj, const std::vector<engine::VertexId>& loop) {
  if (loop.empty() || obj.ends.empty()) return {};
  const engine::Vec3 c = loop_centroid(obj.mesh, loop);
  const engine::VesselEnd* best = nullptr;
  double best_distance = 0.0;
  for (const auto& e : obj.ends) {
    const double d = (e.centre - c).norm();
    if (d <= std::max(0.5, 0.5 * e.radius) && (!best || d < best_distance)) best = &e, best_distance = d;
  }
  return best ? best->name : std::string();
}

}  // namespace sutura::app
