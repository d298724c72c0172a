// The Inspect section: before/after, colour maps, cross-section, snapshot, export, continue.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "panels.hpp"
#include "sutura/app/patch_template.hpp"

namespace sutura::ui {

namespace {

namespace fs = std::filesystem;

// Records and runs the snapshot op waiting in s.pending_snapshot.
void save_pending_snapshot(GuiState& s) {
  const nlohmann::json op = *s.pending_snapshot;
  s.pending_snapshot.reset();
  s.perform(op, "Snapshot saved to " + (s.controller.options().out_dir / op["file"].get<std::string>()).string());
}

// The lumen area along the automatic centreline, before (blue) and after (orange) in one
// frame on one scale from zero, each station at its arc length, the narrowest of each marked;
// then the numbers (the measure op's details: values.before/after.stations, ...).
void profile_plot(const nlohmann::json& details) {
  const nlohmann::json values = details.value("values", nlohmann::json::object());
  const char* kSides[] = {"before", "after"};
  const ImU32 kColours[] = {IM_COL32(40, 90, 200, 255), IM_COL32(230, 120, 20, 255)};
  struct Series {
    std::vector<ImVec2> points;  // (arc length mm, area mm2); open sections are left out
    double length = 0.0;
  } series[2];
  double top = 0.0, right = 0.0;
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json side = values.value(kSides[k], nlohmann::json::object());
    for (const auto& st : side.value("stations", nlohmann::json::array()))
      if (st.contains("area_mm2") && st["area_mm2"].is_number() && st.value("closed", false)) {
        series[k].points.emplace_back(st["arc_length_mm"].get<float>(), st["area_mm2"].get<float>());
        top = std::max(top, st["area_mm2"].get<double>());
      }
    series[k].length = side.value("centreline_length_mm", 0.0);
    right = std::max(right, series[k].length);
  }
  if (!(top > 0.0) || !(right > 0.0)) return;
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 110.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##lumen_profile", size);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(255, 255, 255, 255));
  draw->AddRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(150, 150, 150, 255));
  const auto at = [&](const ImVec2& p) {
    return ImVec2(origin.x + 4.0f + (size.x - 8.0f) * static_cast<float>(p.x / right),
                  origin.y + size.y - 4.0f - (size.y - 8.0f) * static_cast<float>(p.y / (1.05 * top)));
  };
  for (int k = 0; k < 2; ++k) {
    std::vector<ImVec2> screen;
    for (const ImVec2& p : series[k].points) screen.push_back(at(p));
    if (screen.size() >= 2) draw->AddPolyline(screen.data(), static_cast<int>(screen.size()), kColours[k], 0, 2.0f);
    const nlohmann::json side = values.value(kSides[k], nlohmann::json::object());
    if (side.contains("min_area_mm2"))
      draw->AddCircleFilled(at(ImVec2(side["min_area_arc_length_mm"].get<float>(), side["min_area_mm2"].get<float>())), 4.0f,
                            kColours[k]);
  }
  char scale[64];
  std::snprintf(scale, sizeof scale, "%.1f mm2", 1.05 * top);
  draw->AddText(ImVec2(origin.x + 6.0f, origin.y + 2.0f), IM_COL32(90, 90, 90, 255), scale);
  for (int k = 0; k < 2; ++k) {
    const nlohmann::json side = values.value(kSides[k], nlohmann::json::object());
    if (!side.contains("min_area_mm2")) continue;
    const auto& p = side["min_area_point"];
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::ColorConvertU32ToFloat4(kColours[k]));
    ImGui::TextWrapped("%s: narrowest %.2f mm2 at %.1f of %.1f mm, centre (%.1f, %.1f, %.1f)", kSides[k],
                       side["min_area_mm2"].get<double>(), side["min_area_arc_length_mm"].get<double>(),
                       series[k].length, p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    ImGui::PopStyleColor();
  }
  if (values.contains("min_area_change_percent") && values["min_area_change_percent"].is_number())
    ImGui::TextWrapped("Narrowest lumen %+.1f %%. Lumen area (0 to %.1f mm2) along the centreline (0 to %.1f mm).",
                       values["min_area_change_percent"].get<double>(), 1.05 * top, right);
}

void lumen_profile_controls(GuiState& s) {
  const auto why = s.why_not(Command::MeasureCrossSection, "measure");
  const auto* obj = s.selected();
  const auto loops = obj ? obj->mesh.boundary_loops() : std::vector<std::vector<engine::VertexId>>{};
  ImGui::TextWrapped("The lumen along the vessel's automatic centreline between two open ends.");
  const auto centre = [&](int i) { return app::loop_centroid(obj->mesh, loops[static_cast<std::size_t>(i)]); };
  const int n = static_cast<int>(loops.size());
  for (int* which : {&s.profile_from, &s.profile_to}) {
    *which = n > 0 ? std::clamp(*which, 0, n - 1) : 0;
    ImGui::SetNextItemWidth(60);
    ImGui::InputInt(which == &s.profile_from ? "from end" : "to end", which);
    s.widgets.note(which == &s.profile_from ? "from end" : "to end");
    if (n > 0) {
      *which = std::clamp(*which, 0, n - 1);
      const engine::Vec3 c = centre(*which);
      const std::string end = app::end_name(*obj, loops[static_cast<std::size_t>(*which)]);
      ImGui::SameLine();
      ImGui::TextDisabled("%s (%.1f, %.1f, %.1f)", end.empty() ? "" : end.c_str(), c.x(), c.y(), c.z());
    }
  }
  const std::optional<std::string> gate =
      why ? why
          : n < 2 ? std::optional<std::string>("The object needs two open ends.")
          : s.profile_from == s.profile_to ? std::optional<std::string>("Choose two different ends.")
                                           : std::nullopt;
  if (gated_button(s.widgets, "Measure lumen profile", gate) && obj) {
    const std::string name = "profile_" + std::to_string(++s.measure_count);
    const ActionOutcome r =
        s.controller.run(app::lumen_profile_op(obj->name, name, centre(s.profile_from), centre(s.profile_to)));
    if (r.ok) {
      s.last_profile = r.details;
      s.info("Lumen profile measured");
    } else {
      s.error("measure failed: " + r.message);
    }
  }
  if (!s.last_profile.is_null()) profile_plot(s.last_profile);
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
  const auto why_view = s.why_not(Command::ToggleBeforeAfter);
  ImGui::BeginDisabled(why_view.has_value());
  noted_checkbox(s.widgets, "Show before", &s.show_before);
  ImGui::SameLine();
  noted_checkbox(s.widgets, "Side by side", &s.side_by_side);
  ImGui::EndDisabled();
  if (why_view) tooltip_for_last_item(*why_view);

  const auto why_map = s.why_not(Command::ShowColorMap);
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

  s.section_controls_open = noted_tree_node(s.widgets, "Cross-section");
  if (s.section_controls_open) {
    cross_section_controls(s);
    ImGui::TreePop();
  }
  if (noted_tree_node(s.widgets, "Lumen profile")) {
    lumen_profile_controls(s);
    ImGui::TreePop();
  }
  ImGui::Separator();
  ImGui::InputText("snapshot file", s.snapshot_file, sizeof s.snapshot_file);
  // A snapshot shows the after state, or before | after side by side: not the before state
  // alone, so the window's "Show before" view cannot be saved as it is.
  std::optional<std::string> no_snapshot = s.why_not(Command::SaveSnapshot);
  if (!no_snapshot && s.show_before && !s.side_by_side)
    no_snapshot = "A snapshot shows the after state or both side by side: turn off Show before.";
  if (gated_button(s.widgets, "Save snapshot", no_snapshot,
                   "The view as it is (camera, size, colour range) as a PNG in the output "
                   "directory, rendered off-screen like `sutura replay`.")) {
    app::SnapshotView view;
    view.camera = s.shown_camera();
    const float width = s.side_by_side ? 0.5f * s.view_width : s.view_width;
    view.width = std::clamp(int(width), 16, 8192);
    view.height = std::clamp(int(s.view_height), 16, 8192);
    if (const auto cmap = s.view.color_map()) view.range = std::array<float, 2>{cmap->min, cmap->max};
    view.clip = s.clip_plane();
    s.pending_snapshot = app::snapshot_op(s.snapshot_file, view, s.side_by_side, session_field_name(s.field));
    if (!fs::exists(s.controller.options().out_dir / s.snapshot_file)) save_pending_snapshot(s);
  }
  if (s.pending_snapshot && !ImGui::IsPopupOpen("Replace the snapshot?")) ImGui::OpenPopup("Replace the snapshot?");
  if (ImGui::BeginPopupModal("Replace the snapshot?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("%s already exists in the output directory.", s.snapshot_file);
    if (gated_button(s.widgets, "Replace it", std::nullopt)) {
      save_pending_snapshot(s);
      ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (gated_button(s.widgets, "Keep it", std::nullopt)) {
      s.pending_snapshot.reset();
      s.info("Snapshot not saved: change the file name to keep both.");
      ImGui::CloseCurrentPopup();
    }
    ImGui::EndPopup();
  }
  ImGui::InputText("export file", s.export_file, sizeof s.export_file);
  if (gated_button(s.widgets, "Export mesh", s.why_not(Command::ExportMesh)) && s.selected())
    s.perform(app::export_op(s.selected()->name, s.export_file),
              "Exported '" + s.selected()->name + "' to " +
                  (s.controller.options().out_dir / s.export_file).string());
  ImGui::InputText("template file", s.template_file, sizeof s.template_file);
  // The cutting template of the selected object's last patch, proximal at its start.
  std::optional<std::string> no_template = s.why_not(Command::ExportMesh);
  if (!no_template && !s.selected()) no_template = "Select the object the patch is sewn into.";
  if (!no_template) {
    const std::string key = s.selected()->name + '\n' + s.template_file;
    if (key != s.template_key || s.template_revision != s.controller.revision()) {
      s.template_key = key;
      s.template_revision = s.controller.revision();
      s.template_why.reset();
      try {
        s.template_op = app::patch_template_op(s.controller.plan(), s.selected()->name,
                                               app::patch_materials(*s.selected()).size(), s.template_file);
      } catch (const std::invalid_argument& e) {
        s.template_why = e.what();
      }
    }
    no_template = s.template_why;
  }
  if (gated_button(s.widgets, "Save cutting template", no_template,
                   "The last patch as cut from the sheet, at 1:1 (.pdf or .svg): print at 100 % "
                   "and check its 10 mm bar (docs/patch-design.md)."))
    s.perform(s.template_op, "Saved the cutting template to " +
                               (s.controller.options().out_dir / s.template_file).string());
  ImGui::InputText("report file", s.report_file, sizeof s.report_file);
  if (gated_button(s.widgets, "Save plan report", s.why_not(Command::ExportMesh),
                   "The plan report (.html, and a PDF of it beside it): the steps, before and after "
                   "from standard views, the lumen profile, measurements, equilibrium, patch templates "
                   "and materials, with this recording's hash (docs/patch-design.md).")) {
    std::filesystem::path pdf = s.report_file;
    pdf.replace_extension(".pdf");
    s.perform(app::plan_report_op(s.report_file),
              "Saved the plan report to " + (s.controller.options().out_dir / s.report_file).string() + " and " +
                  (s.controller.options().out_dir / pdf).string());
  }
  ImGui::Separator();
  if (gated_button(s.widgets, "Continue planning", s.why_not(Command::ContinuePlanning),
                   "Edit the simulated result further (another round of planning).")) {
    s.stages.continue_planning();
    s.show_before = false;
  }
}

}  // namespace sutura::ui
