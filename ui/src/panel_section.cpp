// Inspect > Cross-section: a plane placed by a click, across the vessel (perpendicular to its
// automatic centreline at the clicked point) or along a coordinate axis; the measure op's
// numbers before and after, and a section view that draws both outlines in the plane.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "panels.hpp"
#include "sutura/app/resect_preview.hpp"

namespace sutura::ui {

namespace {

// The measure op's before/after numbers as a table (its report details: values.before,
// values.after, values.area_change_percent).
void measurement_table(const nlohmann::json& details) {
  const nlohmann::json values = details.value("values", nlohmann::json::object());
  const nlohmann::json before = values.value("before", nlohmann::json::object());
  const nlohmann::json after = values.value("after", nlohmann::json::object());
  static const std::pair<const char*, const char*> kRows[] = {
      {"area_mm2", "area [mm2]"},
      {"equivalent_diameter_mm", "equivalent diameter [mm]"},
      {"min_diameter_mm", "min diameter [mm]"},
      {"max_diameter_mm", "max diameter [mm]"},
      {"perimeter_mm", "perimeter [mm]"}};
  if (!ImGui::BeginTable("measure", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchProp))
    return;
  ImGui::TableSetupColumn("");
  ImGui::TableSetupColumn("before");
  ImGui::TableSetupColumn("after");
  ImGui::TableHeadersRow();
  const auto cell = [](const nlohmann::json& side, const char* key) {
    ImGui::TableNextColumn();
    if (side.contains(key) && side[key].is_number()) ImGui::Text("%.3f", side[key].get<double>());
    else ImGui::TextDisabled("-");
  };
  for (const auto& [key, label] : kRows) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(label);
    cell(before, key);
    cell(after, key);
  }
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextUnformatted("outline");
  for (const auto* side : {&before, &after}) {
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(side->value("closed", false) ? "closed" : "open");
  }
  ImGui::EndTable();
  if (values.contains("area_change_percent") && values["area_change_percent"].is_number() &&
      std::isfinite(values["area_change_percent"].get<double>()))
    ImGui::Text("area change: %+.1f %%", values["area_change_percent"].get<double>());
}

// Brings s.section_plane up to date with the clicked origin, the chosen normal and the
// workspace (across the vessel: cut_at on the selected object's centreline, as the Resect
// tool places its cuts).
void refresh_section_plane(GuiState& s) {
  const app::SceneObject* obj = s.selected();
  if (!s.plane_origin || obj == nullptr) {
    s.section_plane.reset();
    s.section_error.clear();
    s.section_plane_key.clear();
    return;
  }
  char key[192];
  std::snprintf(key, sizeof key, "%llu/%zu/%a,%a,%a/%d", static_cast<unsigned long long>(s.controller.workspace_revision()),
                s.object, s.plane_origin->x(), s.plane_origin->y(), s.plane_origin->z(), s.plane_axis);
  if (key == s.section_plane_key) return;
  s.section_plane_key = key;
  s.section_plane.reset();
  s.section_error.clear();
  if (s.plane_axis < 3) {
    engine::Vec3 n = engine::Vec3::Zero();
    n[s.plane_axis] = 1.0;
    s.section_plane = engine::Plane{*s.plane_origin, n};
    s.section_extent = 0.3 * obj->mesh.bounds().diagonal().norm();
    return;
  }
  const engine::CentrelineTree* tree = s.selected_centreline();
  if (tree == nullptr) {
    s.section_error = "the vessel's centreline cannot be made: " + s.centreline_error;
    return;
  }
  try {
    const app::SectionCut cut = app::cut_at(obj->mesh, *tree, *s.plane_origin);
    s.section_plane = engine::Plane{cut.plane.origin, cut.plane.normal};
    s.section_extent = 1.3 * cut.wall_distance;
  } catch (const std::exception& e) {
    s.section_error = e.what();
  }
}

// A length for the scale bar: 1, 2 or 5 times a power of ten, at most `most` mm.
double scale_bar_length(double most) {
  double p = std::pow(10.0, std::floor(std::log10(most)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * p <= most) return m * p;
  return p;
}

// Both outlines of the last measured section in its plane, on one scale, centred on the
// plane's origin: before blue, after orange (as the lumen profile), with the centroids and a
// scale bar. The in-plane axes are fixed by the normal alone (Vec3::unitOrthogonal).
void section_view(const app::SectionPair& section, const engine::Plane& plane) {
  const engine::Vec3 n = plane.normal.normalized();
  const engine::Vec3 u = n.unitOrthogonal(), v = n.cross(u);
  const auto in_plane = [&](const engine::Vec3& p) {
    const engine::Vec3 d = p - plane.origin;
    return std::array<double, 2>{d.dot(u), d.dot(v)};
  };
  double half = 0.0;
  for (const auto* c : {&section.before, &section.after})
    for (const auto& p : c->points) {
      const auto q = in_plane(p);
      half = std::max({half, std::abs(q[0]), std::abs(q[1])});
    }
  if (!(half > 0.0)) return;
  half *= 1.1;
  const float side = std::min(ImGui::GetContentRegionAvail().x, 240.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##section_view", ImVec2(side, side));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 corner(origin.x + side, origin.y + side);
  draw->AddRectFilled(origin, corner, IM_COL32(255, 255, 255, 255));
  draw->AddRect(origin, corner, IM_COL32(150, 150, 150, 255));
  const float scale = static_cast<float>(0.5 * side / half);
  const ImVec2 centre(origin.x + 0.5f * side, origin.y + 0.5f * side);
  const auto at = [&](const engine::Vec3& p) {
    const auto q = in_plane(p);
    return ImVec2(centre.x + scale * static_cast<float>(q[0]), centre.y - scale * static_cast<float>(q[1]));
  };
  draw->AddLine(ImVec2(centre.x - 6, centre.y), ImVec2(centre.x + 6, centre.y), IM_COL32(170, 170, 170, 255));
  draw->AddLine(ImVec2(centre.x, centre.y - 6), ImVec2(centre.x, centre.y + 6), IM_COL32(170, 170, 170, 255));
  const ImU32 kColours[] = {IM_COL32(40, 90, 200, 255), IM_COL32(230, 120, 20, 255)};
  int k = 0;
  for (const auto* c : {&section.before, &section.after}) {
    std::vector<ImVec2> screen;
    for (const auto& p : c->points) screen.push_back(at(p));
    if (screen.size() >= 2)
      draw->AddPolyline(screen.data(), static_cast<int>(screen.size()), kColours[k],
                        c->closed ? ImDrawFlags_Closed : ImDrawFlags_None, 2.0f);
    draw->AddCircleFilled(at(c->centroid), 3.0f, kColours[k]);
    ++k;
  }
  const double bar = scale_bar_length(0.4 * 2.0 * half);
  const float bar_px = scale * static_cast<float>(bar);
  const ImVec2 b0(origin.x + 8.0f, corner.y - 10.0f), b1(origin.x + 8.0f + bar_px, corner.y - 10.0f);
  draw->AddLine(b0, b1, IM_COL32(60, 60, 60, 255), 2.0f);
  char label[32];
  std::snprintf(label, sizeof label, "%g mm", bar);
  draw->AddText(ImVec2(b0.x, b0.y - ImGui::GetTextLineHeight() - 2.0f), IM_COL32(60, 60, 60, 255), label);
  ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kColours[0]), "before%s", section.before.closed ? "" : " (open)");
  ImGui::SameLine();
  ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(kColours[1]), "after%s", section.after.closed ? "" : " (open)");
  ImGui::SameLine();
  ImGui::TextDisabled("seen from the normal's side");
}

}  // namespace

void cross_section_controls(GuiState& s) {
  const auto why = s.why_not(Command::MeasureCrossSection, "measure");
  ImGui::TextWrapped("Click the surface to place the plane; choose its direction.");
  if (noted_radio(s.widgets, "across the vessel", s.plane_axis == 3)) s.plane_axis = 3;
  tooltip_for_last_item("Perpendicular to the vessel's automatic centreline at the clicked point, "
                        "through the middle of the lumen there.");
  for (int axis = 0; axis < 3; ++axis) {
    static const char* kAxes[] = {"normal x", "normal y", "normal z"};
    if (noted_radio(s.widgets, kAxes[axis], s.plane_axis == axis)) s.plane_axis = axis;
    if (axis < 2) ImGui::SameLine();
  }
  refresh_section_plane(s);
  if (s.section_plane) {
    const auto& o = s.section_plane->origin;
    ImGui::Text("plane through (%.1f, %.1f, %.1f) mm", o.x(), o.y(), o.z());
  } else if (!s.section_error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.1f, 0.1f, 1.0f));
    ImGui::TextWrapped("No plane here: %s", s.section_error.c_str());
    ImGui::PopStyleColor();
  }
  const std::optional<std::string> gate =
      why ? why
          : !s.plane_origin ? std::optional<std::string>("Click the surface to place the plane first.")
          : !s.section_plane ? std::optional<std::string>("No plane here: " + s.section_error)
                             : std::nullopt;
  if (gated_button(s.widgets, "Measure cross-section", gate) && s.selected()) {
    const engine::Plane plane = *s.section_plane;
    const std::string name = "section_" + std::to_string(++s.measure_count);
    const ActionOutcome r = s.controller.run(app::measure_op(s.selected()->name, name, plane.origin, plane.normal));
    if (r.ok) {
      s.last_measure = r.details;
      s.last_section.reset();
      s.last_section_revision = s.controller.workspace_revision();
      try {
        s.last_section = app::measure_section(*s.selected(), plane, 0.0);  // the op's own outlines
        s.last_section_plane = plane;
      } catch (const std::exception&) {
        // The op succeeded on the same shapes, so this does not happen; the numbers still show.
      }
      s.info("Cross-section measured");
    } else {
      s.error("measure failed: " + r.message);
    }
  }
  if (!s.last_measure.is_null() && !s.controller.busy() &&
      s.last_section_revision != s.controller.workspace_revision()) {
    s.last_measure = nullptr;  // of objects that have changed since
    s.last_section.reset();
  }
  if (!s.last_measure.is_null()) measurement_table(s.last_measure);
  if (s.last_section) section_view(*s.last_section, s.last_section_plane);
}

}  // namespace sutura::ui
