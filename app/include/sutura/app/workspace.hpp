#pragma once
// The objects a session works on, by name, in the order they were created.
#include <optional>
#include <string>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/surface_attributes.hpp"

namespace sutura::app {

struct SceneObject {
  std::string name;
  engine::SurfaceMesh mesh;    ///< current state
  engine::SurfaceMesh before;  ///< pre-operative state: the mesh as generated or loaded
  /// Everything simulated or drawn on `mesh`, carried across every edit by the engine
  /// (state, rest shape and pending y0, materials, constraints, loads, velocity, reference
  /// positions, marks).
  engine::SurfaceAttributes sim;
};

class Workspace {
 public:
  /// Adds an object at rest (rest state congruent with the mesh, identity nodal triads,
  /// default material); throws std::invalid_argument if the name is taken.
  SceneObject& add(std::string name, engine::SurfaceMesh mesh);
  /// nullptr when no object has that name.
  [[nodiscard]] SceneObject* find(const std::string& name);
  [[nodiscard]] const SceneObject* find(const std::string& name) const;
  [[nodiscard]] const std::vector<SceneObject>& objects() const { return objects_; }
  /// "a, b, c" for messages.
  [[nodiscard]] std::string names() const;

 private:
  std::vector<SceneObject> objects_;
};

}  // namespace sutura::app
