#pragma once
// What the 3-D view draws: the objects' views (app/object_view.hpp, the snapshots' path:
// current and before state, optional colour field), cached per workspace revision, with live
// positions patched in while a simulation runs; and the scene built from them plus the GUI's
// overlays.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sutura/app/object_view.hpp"
#include "sutura/app/workspace.hpp"
#include "sutura/render/scene.hpp"
#include "sutura/ui/session_controller.hpp"

namespace sutura::ui {

enum class ViewField { None, Displacement, MembraneStrain, Bending };
/// The session's field name ("none", "displacement", "membrane_strain", "bending").
const char* session_field_name(ViewField f);

/// The session's field of a view field.
app::Field session_field(ViewField f);

class ViewCache {
 public:
  /// Rebuilds when `revision` or `field` changed since the last call. A field some object
  /// cannot provide is dropped for that object and explained by field_problem().
  void update(const app::Workspace& workspace, std::uint64_t revision, ViewField field);
  /// Overwrites the positions of the objects in `live` (a running simulation).
  void apply_live(const LiveProgress& live);

  [[nodiscard]] const std::vector<app::ObjectView>& current() const { return current_; }
  [[nodiscard]] const std::vector<app::ObjectView>& before() const { return before_; }
  [[nodiscard]] const std::optional<std::string>& field_problem() const { return problem_; }
  /// Colour map for the current field over both states, or nullopt without a field.
  [[nodiscard]] std::optional<render::ColorMap> color_map() const;

 private:
  std::vector<app::ObjectView> current_, before_;
  std::optional<std::string> problem_;
  std::uint64_t revision_ = ~std::uint64_t{0};
  std::uint64_t live_revision_ = 0;
  ViewField field_ = ViewField::None;
};

/// GUI overlays on top of the objects.
struct Overlays {
  std::vector<render::PolylineItem> lines;
  std::vector<render::PointsItem> points;
};

/// Surfaces (wireframe optional), boundary loops, fixed vertices, then `overlays`.
render::Scene make_scene(const std::vector<app::ObjectView>& objects, const Overlays& overlays,
                         const std::optional<render::ColorMap>& color_map, bool wireframe);

}  // namespace sutura::ui
