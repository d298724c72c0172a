#include "sutura/app/object_view.hpp"

#include <algorithm>

#include "sutura/app/simulation.hpp"
#include "sutura/engine/measure/vertex_fields.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::app {

namespace {

render::Point3 point(const engine::Vec3& p) { return {float(p.x()), float(p.y()), float(p.z())}; }

// The per-element measures of the shell model whose run produced the current state
// (SurfaceAttributes::state_model; Model 1, the default, before any run) averaged to the
// vertices with face-area weights, for the current state with its simulated nodal rotations. The before
// state's are those `unload` kept (an imaged vessel under its loads), or zero everywhere for a
// stress-free reference (its topology may differ from today's after incisions and sutures, so
// they are not recomputed).
std::vector<float> element_field(Field field, const SceneObject& obj, const engine::SurfaceMesh& state) {
  if (&state != &obj.mesh) {
    const engine::VertexMeasures& b = obj.before_measures;
    const std::vector<double>& v = field == Field::MembraneStrain ? b.membrane_strain
                                   : field == Field::Bending      ? b.bending_curvature
                                                                  : b.energy_density;
    if (v.size() != state.num_vertices()) return std::vector<float>(state.num_vertices(), 0.0f);
    return std::vector<float>(v.begin(), v.end());
  }
  const auto model = state_model_of(obj);
  const engine::ShellProblem problem{&state.faces(), &obj.sim.rest, &obj.sim.materials,
                                     &obj.sim.face_material, state.num_vertices()};
  const engine::ElementMeasures m = model->measures(problem, obj.sim.state);
  const std::vector<double>& per_face = field == Field::MembraneStrain ? m.membrane_strain
                                        : field == Field::Bending      ? m.bending_curvature
                                                                       : m.energy_density;
  const std::vector<double> per_vertex = engine::face_to_vertex(state, per_face);
  return std::vector<float>(per_vertex.begin(), per_vertex.end());
}

}  // namespace

std::vector<float> field_values(Field field, const SceneObject& obj, const engine::SurfaceMesh& state) {
  if (field == Field::MembraneStrain || field == Field::Bending || field == Field::EnergyDensity)
    return element_field(field, obj, state);
  std::vector<float> v(state.num_vertices());
  const bool moved = &state == &obj.mesh && obj.sim.reference.size() == v.size();
  for (std::size_t i = 0; i < v.size(); ++i) {
    const engine::Vec3& p = state.positions()[i];
    switch (field) {
      case Field::X: v[i] = static_cast<float>(p.x()); break;
      case Field::Y: v[i] = static_cast<float>(p.y()); break;
      case Field::Z: v[i] = static_cast<float>(p.z()); break;
      case Field::Displacement: v[i] = moved ? static_cast<float>((p - obj.sim.reference[i]).norm()) : 0.0f; break;
      default: break;
    }
  }
  return v;
}

std::string field_label(Field field) {
  switch (field) {
    case Field::Displacement: return "displacement [mm]";
    case Field::X: return "x [mm]";
    case Field::Y: return "y [mm]";
    case Field::Z: return "z [mm]";
    case Field::MembraneStrain: return "max principal membrane strain [-]";
    case Field::Bending: return "curvature change [1/mm]";
    case Field::EnergyDensity: return "strain energy density [N/mm]";
    case Field::None: break;
  }
  return {};
}

ObjectView object_view(const SceneObject& obj, const engine::SurfaceMesh& state, render::Color color,
                       const ViewContent& content) {
  ObjectView a;
  a.name = obj.name;
  a.positions = state.flat_positions();
  a.plan = plan_drawing(obj, state, content.marks);
  if (content.field != Field::None) a.scalars = field_values(content.field, obj, state);
  if (content.boundaries) {
    for (const auto& loop : state.boundary_loops()) {
      std::vector<render::Point3> pts;
      pts.reserve(loop.size());
      for (auto v : loop) pts.push_back(point(state.position(v)));
      a.loops.push_back(std::move(pts));
    }
  }
  // Held vertices: in the current state where they are; in the before state at their
  // pre-operative positions (carried across edits), so both sides of a comparison show them.
  const auto& fixed = obj.sim.constraints.fixed;
  if (content.marks && &state == &obj.mesh) {
    for (std::size_t v = 0; v < std::min(fixed.size(), state.num_vertices()); ++v)
      if (fixed[v] != 0) a.held.push_back(point(state.position(engine::VertexId(v))));
  } else if (content.marks && &state == &obj.before && obj.sim.reference.size() == obj.mesh.num_vertices()) {
    for (std::size_t v = 0; v < std::min(fixed.size(), obj.sim.reference.size()); ++v)
      if (fixed[v] != 0) a.held.push_back(point(obj.sim.reference[v]));
  }
  a.color = color;
  return a;
}

render::Scene scene_of(const std::vector<ObjectView>& views, const std::optional<render::ColorMap>& color_map,
                       bool wireframe) {
  render::Scene scene;
  scene.background = kViewBackground;
  for (const auto& a : views) {
    add_plan_surfaces(scene, a.positions, color_map ? std::span<const float>(a.scalars) : std::span<const float>(),
                      a.plan, a.color, wireframe);
    for (const auto& loop : a.loops) {
      render::PolylineItem line;
      line.points = loop;
      line.closed = true;
      line.color = {0.15f, 0.15f, 0.15f};
      line.width_px = 2.5f;
      scene.polylines.push_back(std::move(line));
    }
    if (!a.held.empty()) {
      render::PointsItem held;
      held.points = a.held;
      held.color = kHeldColor;
      held.size_px = 7.0f;
      scene.points.push_back(std::move(held));
    }
    add_plan_lines(scene, a.plan);
  }
  scene.color_map = color_map;
  return scene;
}

}  // namespace sutura::app
