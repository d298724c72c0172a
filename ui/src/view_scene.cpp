#include "view_scene.hpp"

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>

#include "sutura/engine/measure/vertex_fields.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::ui {

namespace {


render::Point3 point(const engine::Vec3& p) { return {float(p.x()), float(p.y()), float(p.z())}; }

std::vector<float> to_float(const std::vector<double>& v) { return {v.begin(), v.end()}; }

// Per-vertex field values of `state` (the object's current mesh or its before mesh).
std::optional<std::vector<float>> field_values(ViewField field, const app::SceneObject& obj,
                                               bool current, std::string& problem) {
  const engine::SurfaceMesh& mesh = current ? obj.mesh : obj.before;
  if (field == ViewField::Displacement) {
    // From each vertex's pre-operative position, carried across edits (as snapshots do).
    if (!current) return std::vector<float>(mesh.num_vertices(), 0.0f);
    if (obj.sim.reference.size() != mesh.num_vertices()) {
      problem = "Object '" + obj.name + "' has no reference positions for its vertices.";
      return std::nullopt;
    }
    return to_float(engine::displacement_magnitude(obj.sim.reference, mesh.positions()));
  }
  // Model 1's per-element measures; the before state's are those `unload` kept (an imaged
  // vessel under its loads), or zero for a stress-free reference.
  if (!current) {
    const std::vector<double>& v = field == ViewField::MembraneStrain
                                       ? obj.before_measures.membrane_strain
                                       : obj.before_measures.bending_curvature;
    if (v.size() != mesh.num_vertices()) return std::vector<float>(mesh.num_vertices(), 0.0f);
    return to_float(v);
  }
  const auto model = engine::make_corotational_shell();
  const engine::ShellProblem p{&mesh.faces(), &obj.sim.rest, &obj.sim.materials,
                               &obj.sim.face_material, mesh.num_vertices()};
  const auto measures = engine::face_to_vertex(mesh, model->measures(p, obj.sim.state));
  return to_float(field == ViewField::MembraneStrain ? measures.membrane_strain
                                                     : measures.bending_curvature);
}

ObjectArrays arrays_for(const app::SceneObject& obj, bool current, render::Color color) {
  const engine::SurfaceMesh& mesh = current ? obj.mesh : obj.before;
  ObjectArrays a;
  a.name = obj.name;
  a.positions = mesh.flat_positions();
  a.plan = app::plan_drawing(obj, mesh, true);
  a.color = color;
  for (const auto& loop : mesh.boundary_loops()) {
    std::vector<render::Point3> pts;
    for (auto v : loop) pts.push_back(point(mesh.position(v)));
    a.loops.push_back(std::move(pts));
  }
  if (current) {
    const auto& fixed = obj.sim.constraints.fixed;
    for (std::size_t v = 0; v < std::min(fixed.size(), mesh.num_vertices()); ++v)
      if (fixed[v] != 0) a.fixed.push_back(point(mesh.position(engine::VertexId(v))));
  }
  return a;
}

}  // namespace

const char* session_field_name(ViewField f) {
  switch (f) {
    case ViewField::Displacement: return "displacement";
    case ViewField::MembraneStrain: return "membrane_strain";
    case ViewField::Bending: return "bending";
    case ViewField::None: break;
  }
  return "none";
}

const char* field_label(ViewField f) {
  switch (f) {
    case ViewField::Displacement: return "displacement [mm]";
    case ViewField::MembraneStrain: return "max principal membrane strain [-]";
    case ViewField::Bending: return "curvature change [1/mm]";
    case ViewField::None: break;
  }
  return "";
}

void ViewCache::update(const app::Workspace& workspace, std::uint64_t revision, ViewField field) {
  if (revision == revision_ && field == field_) return;
  revision_ = revision;
  field_ = field;
  current_.clear();
  before_.clear();
  problem_.reset();
  const auto& objects = workspace.objects();
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const render::Color color = render::object_color(i);
    current_.push_back(arrays_for(objects[i], true, color));
    before_.push_back(arrays_for(objects[i], false, color));
    if (field == ViewField::None) continue;
    std::string problem;
    auto now = field_values(field, objects[i], true, problem);
    auto then = field_values(field, objects[i], false, problem);
    if (now && then) {
      current_.back().scalars = std::move(*now);
      before_.back().scalars = std::move(*then);
    } else {
      problem_ = problem;
    }
  }
}

void ViewCache::apply_live(const LiveProgress& live) {
  if (live.positions_revision == live_revision_) return;
  live_revision_ = live.positions_revision;
  for (const auto& [name, x] : live.positions)
    for (auto& a : current_)
      if (a.name == name && a.positions.size() == 3 * x.size()) {
        for (std::size_t i = 0; i < x.size(); ++i)
          for (int k = 0; k < 3; ++k) a.positions[3 * i + k] = float(x[i][k]);
        a.scalars.clear();  // fields are computed for finished states only
      }
}

std::optional<render::ColorMap> ViewCache::color_map() const {
  if (field_ == ViewField::None) return std::nullopt;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (const auto* set : {&current_, &before_})
    for (const auto& a : *set)
      for (float s : a.scalars) lo = std::min(lo, s), hi = std::max(hi, s);
  if (lo > hi) return std::nullopt;
  // A constant field still needs a range, one that a float can tell from its start.
  if (!(hi > lo)) hi = lo + std::max(1.0f, 1e-3f * std::abs(lo));
  render::ColorMap c;
  c.min = lo;
  c.max = hi;
  c.label = field_label(field_);
  return c;
}

render::Scene make_scene(const std::vector<ObjectArrays>& objects, const Overlays& overlays,
                         const std::optional<render::ColorMap>& color_map, bool wireframe) {
  render::Scene scene;
  scene.background = {0.93f, 0.94f, 0.96f};
  for (const auto& a : objects) {
    app::add_plan_surfaces(scene, a.positions, color_map ? std::span<const float>(a.scalars) : std::span<const float>(),
                           a.plan, a.color, wireframe);
    for (const auto& loop : a.loops) {
      render::PolylineItem line;
      line.points = loop;
      line.closed = true;
      line.color = {0.15f, 0.15f, 0.15f};
      line.width_px = 2.0f;
      scene.polylines.push_back(std::move(line));
    }
    if (!a.fixed.empty()) {
      render::PointsItem fixed;
      fixed.points = a.fixed;
      fixed.color = {0.95f, 0.75f, 0.05f};
      fixed.size_px = 7.0f;
      scene.points.push_back(std::move(fixed));
    }
    app::add_plan_lines(scene, a.plan);
  }
  scene.polylines.insert(scene.polylines.end(), overlays.lines.begin(), overlays.lines.end());
  scene.points.insert(scene.points.end(), overlays.points.begin(), overlays.points.end());
  scene.color_map = color_map;
  return scene;
}

}  // namespace sutura::ui
