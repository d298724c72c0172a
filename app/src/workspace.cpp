#include "sutura/app/workspace.hpp"

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

}  // namespace sutura::app
