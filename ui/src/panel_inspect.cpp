// The Inspect section: before/after, colour maps, cross-section, snapshot, export, continue.
#include <cmath>
#include <cstdio>
#include <string>

#include "panels.hpp"

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

void cross_section_controls(GuiState& s) {
  const auto why = s.why_not(Action::MeasureCrossSection, "measure");
  ImGui::TextWrapped("Click the surface to place the plane's origin; choose its normal.");
  for (int axis = 0; axis < 3; ++axis) {
    static const char* kAxes[] = {"normal x", "normal y", "normal z"};
    if (noted_radio(s.widgets, kAxes[axis], s.plane_axis == axis)) s.plane_axis = axis;
    if (axis < 2) ImGui::SameLine();
  }
  if (s.plane_origin)
    ImGui::Text("origin (%.1f, %.1f, %.1f) mm", s.plane_origin->x(), s.plane_origin->y(),
                s.plane_origin->z());
  const std::optional<std::string> gate =
      why ? why
          : (!s.plane_origin ? std::optional<std::string>("Click the surface to place the plane first.")
                             : std::nullopt);
  if (gated_button(s.widgets, "Measure cross-section", gate) && s.selected()) {
    engine::Vec3 n = engine::Vec3::Zero();
    n[s.plane_axis] = 1.0;
    const std::string name = "section_" + std::to_string(++s.measure_count);
    const ActionOutcome r = s.controller.run(measure_op(s.selected()->name, name, *s.plane_origin, n));
    if (r.ok) {
      s.last_measure = r.details;
      s.info("Cross-section measured");
    } else {
      s.error("measure failed: " + r.message);
    }
  }
  if (!s.last_measure.is_null()) measurement_table(s.last_measure);
}

// Whether the simulated shape is a stable equilibrium (the relaxation's check), in colour,
// with the full sentence as a tooltip.
void equilibrium_line(const nlohmann::json& eq) {
  const bool stable = eq.value("stable", false);
  const int modes = eq.value("negative_modes", -1);
  char text[160];
  if (stable) std::snprintf(text, sizeof text, "Equilibrium: stable");
  else if (modes > 0) std::snprintf(text, sizeof text, "Equilibrium: NOT stable (%d unstable mode%s)", modes, modes > 1 ? "s" : "");
  else std::snprintf(text, sizeof text, "Equilibrium: marginal or not assessed");
  ImGui::TextColored(stable ? ImVec4(0.1f, 0.55f, 0.2f, 1.0f) : ImVec4(0.8f, 0.1f, 0.1f, 1.0f), "%s", text);
  std::string tip = eq.value("summary", std::string());
  if (const int escapes = eq.value("escapes", 0); escapes > 0)
    tip += "\nPushed off an unstable equilibrium " + std::to_string(escapes) +
           " time(s) along an unstable mode and settled again.";
  if (!tip.empty()) tooltip_for_last_item(tip);
}

}  // namespace

void inspect_section(GuiState& s) {
  if (s.stages.stage() == Stage::Inspect && s.last_equilibrium.is_object())
    equilibrium_line(s.last_equilibrium);
  const auto why_view = s.why_not(Action::ToggleBeforeAfter);
  ImGui::BeginDisabled(why_view.has_value());
  noted_checkbox(s.widgets, "Show before", &s.show_before);
  ImGui::SameLine();
  noted_checkbox(s.widgets, "Side by side", &s.side_by_side);
  ImGui::EndDisabled();
  if (why_view) tooltip_for_last_item(*why_view);

  const auto why_map = s.why_not(Action::ShowColorMap);
  static const char* kFields[] = {"plain", "displacement", "membrane strain", "bending"};
  ImGui::TextUnformatted("Colour map:");
  ImGui::BeginDisabled(why_map.has_value());
  for (int f = 0; f < 4; ++f) {
    if (f == 1 || f == 3) ImGui::SameLine();
    if (noted_radio(s.widgets, kFields[f], static_cast<int>(s.field) == f))
      s.field = static_cast<ViewField>(f);
  }
  ImGui::EndDisabled();
  if (why_map) tooltip_for_last_item(*why_map);
  if (s.view.field_problem()) ImGui::TextWrapped("%s", s.view.field_problem()->c_str());

  if (noted_tree_node(s.widgets, "Cross-section")) {
    cross_section_controls(s);
    ImGui::TreePop();
  }
  ImGui::Separator();
  ImGui::InputText("snapshot file", s.snapshot_file, sizeof s.snapshot_file);
  if (gated_button(s.widgets, "Save snapshot", s.why_not(Action::SaveSnapshot),
                   "PNG in the output directory, rendered off-screen like `sutura replay`."))
    s.perform(snapshot_op(s.snapshot_file, 1280, 960, s.side_by_side, session_field_name(s.field)),
              "Snapshot saved to " + (s.controller.options().out_dir / s.snapshot_file).string());
  ImGui::InputText("export file", s.export_file, sizeof s.export_file);
  if (gated_button(s.widgets, "Export mesh", s.why_not(Action::ExportMesh)) && s.selected())
    s.perform(export_op(s.selected()->name, s.export_file),
              "Exported '" + s.selected()->name + "' to " +
                  (s.controller.options().out_dir / s.export_file).string());
  ImGui::Separator();
  if (gated_button(s.widgets, "Continue planning", s.why_not(Action::ContinuePlanning),
                   "Edit the simulated result further (another round of planning).")) {
    s.stages.continue_planning();
    s.show_before = false;
  }
}

}  // namespace sutura::ui
