#pragma once
// The objects a session works on, by name, in the order they were created.
#include <optional>
#include <string>
#include <vector>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/material.hpp"
#include "sutura/engine/shell/rest_state.hpp"
#include "sutura/engine/sim/constraints.hpp"
#include "sutura/engine/sim/loads.hpp"

namespace sutura::app {

/// Simulation data of one object, kept apart from its topology: per-element rest state,
/// materials, constraints, loads and the simulated state.
struct SimulationData {
  engine::ShellState state;      ///< x mirrors SceneObject::mesh positions after every run
  engine::RestState rest;        ///< per element (stress-free reference)
  std::vector<engine::ShellMaterial> materials{engine::ShellMaterial{}};
  std::vector<int> face_material;  ///< per face, index into materials
  engine::Constraints constraints;
  engine::Loads applied_loads;   ///< loads already brought to equilibrium by a solve
  engine::Loads pending_loads;   ///< loads defined since; ramped in by the next solve
  double pending_factor = 0.0;   ///< fraction of pending_loads in equilibrium now, [0, 1)
  Eigen::VectorXd velocity;      ///< per DOF of the last dynamics run; empty = at rest
  /// Per vertex: where its material point was before the operation (carried across edits by
  /// the parent maps), for displacement fields and probes.
  std::vector<engine::Vec3> reference;
  /// y0 of the sutures made since the last relaxation (paper, Sec. 2.3): the rest shape the
  /// next relaxing run starts from; `rest` is x0. Empty = nothing to relax.
  std::optional<engine::RestState> relax_from;
  double relax_s = 0.0;  ///< how far a part-way relaxation got, [0, 1)
};

/// What the surgeon did to an object, for drawing: vertex chains of the current mesh.
struct SurgicalMarks {
  std::vector<std::vector<engine::VertexId>> incisions;  ///< both lips of each cut
  std::vector<std::vector<engine::VertexId>> sutures;    ///< merged vertices of each seam
};

struct SceneObject {
  std::string name;
  engine::SurfaceMesh mesh;    ///< current state
  engine::SurfaceMesh before;  ///< pre-operative state: the mesh as generated or loaded
  SimulationData sim;
  SurgicalMarks marks;
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
