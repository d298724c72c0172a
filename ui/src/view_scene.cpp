#include "view_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sutura::ui {

const char* session_field_name(ViewField f) {
  switch (f) {
    case ViewField::Displacement: return "displacement";
    case ViewField::MembraneStrain: return "membrane_strain";
    case ViewField::Bending: return "bending";
    case ViewField::None: break;
  }
  return "none";
}

app::Field session_field(ViewField f) {
  switch (f) {
    case ViewField::Displacement: return app::Field::Displacement;
    case ViewField::MembraneStrain: return app::Field::MembraneStrain;
    case ViewField::Bending: return app::Field::Bending;
    case ViewField::None: break;
  }
  return app::Field::None;
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
    const app::SceneObject& obj = objects[i];
    app::ViewContent content;
    content.field = session_field(field);
    // Displacement needs each vertex's pre-operative position; without them the field is
    // dropped for this object (and said why) rather than drawn as zero.
    if (field == ViewField::Displacement && !app::has_reference_positions(obj)) {
      problem_ = "Object '" + obj.name + "' has no reference positions for its vertices.";
      content.field = app::Field::None;
    }
    const render::Color color = render::object_color(i);
    current_.push_back(app::object_view(obj, obj.mesh, color, content));
    before_.push_back(app::object_view(obj, obj.before, color, content));
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
  c.label = app::field_label(session_field(field_));
  return c;
}

render::Scene make_scene(const std::vector<app::ObjectView>& objects, const Overlays& overlays,
                         const std::optional<render::ColorMap>& color_map, bool wireframe) {
  render::Scene scene = app::scene_of(objects, color_map, wireframe);
  scene.polylines.insert(scene.polylines.end(), overlays.lines.begin(), overlays.lines.end());
  scene.points.insert(scene.points.end(), overlays.points.begin(), overlays.points.end());
  return scene;
}

}  // namespace sutura::ui
