// The Resect tool (Plan): two clicks on the vessel wall place two cut planes across it; the
// band between them is removed and, by default, the two ends are sewn together end to end.
// The preview is the resect op itself run on the current mesh (resect_preview.hpp).
#include <cstdio>

#include "panels.hpp"

namespace sutura::ui {

namespace {

// Brings s.resect_preview up to date with the clicks, the reach and the workspace.
void refresh_preview(GuiState& s, const app::SceneObject& obj, const engine::CentrelineTree& tree) {
  std::string key = std::to_string(s.controller.revision()) + "/" + std::to_string(s.object) + "/";
  char buf[64];
  for (const auto& p : s.resect.clicks) {
    std::snprintf(buf, sizeof buf, "%a,%a,%a;", p.x(), p.y(), p.z());
    key += buf;
  }
  std::snprintf(buf, sizeof buf, "/%a", double(s.resect.reach));
  key += buf;
  if (key == s.resect_preview_key) return;
  s.resect_preview = app::preview_resection(obj.mesh, tree, s.resect.clicks, s.resect.reach);
  s.resect_preview_key = key;
}

}  // namespace

void resect_controls(GuiState& s) {
  ImGui::TextWrapped("Click the vessel wall where each cut goes: the cut runs straight across the "
                     "vessel, perpendicular to its centreline. Two cuts remove the band between "
                     "them (a third click starts again).");
  const app::SceneObject* obj = s.selected();
  const engine::CentrelineTree* tree = obj ? s.selected_centreline() : nullptr;
  if (obj && !tree) ImGui::TextWrapped("The cuts follow the vessel's centreline, which cannot be made: %s",
                                       s.centreline_error.c_str());
  if (tree) {
    refresh_preview(s, *obj, *tree);
    const app::ResectPreview& p = s.resect_preview;
    for (std::size_t k = 0; k < p.planes.size(); ++k) {
      const auto& o = p.planes[k].origin;
      ImGui::Text("Cut %zu at (%.1f, %.1f, %.1f) mm, lumen %.1f mm across", k + 1, o.x(), o.y(), o.z(),
                  p.cuts[k].diameter);
    }
    if (!p.error.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.75f, 0.05f, 0.05f, 1.0f));
      ImGui::TextWrapped("%s", p.error.c_str());
      ImGui::PopStyleColor();
    } else if (p.planes.size() == 2) {
      ImGui::TextWrapped("Removes %zu faces, %.1f mm2 of wall (red).", p.removed_faces, p.removed_area);
    }
  }
  noted_checkbox(s.widgets, "Sew the ends together (end-to-end anastomosis)", &s.resect.anastomosis);
  number_field("cut reach [mm]", &s.resect.reach, 0.0f, 30.0f, 0.5f, "%.1f");
  tooltip_for_last_item("Only the wall within this distance of a cut's centre is cut, so that a cut "
                        "across the aorta leaves a branch beside it alone. 0: a quarter more than the "
                        "farthest wall of the cuts from their centres.");
  std::optional<std::string> why;
  if (s.resect.clicks.size() < 2) why = "Click the two places to cut first.";
  else if (!tree) why = "The vessel's centreline cannot be made.";
  else if (!s.resect_preview.error.empty()) why = s.resect_preview.error;
  if (gated_button(s.widgets, "Resect", why)) commit_resection(s);
  ImGui::SameLine();
  if (ImGui::Button("Cancel##resect")) cancel_draft(s);
}

void commit_resection(GuiState& s) {
  const app::SceneObject* obj = s.selected();
  // The preview of these clicks on this mesh (the panel that refreshes it may be collapsed).
  const engine::CentrelineTree* tree = obj ? s.selected_centreline() : nullptr;
  if (tree) refresh_preview(s, *obj, *tree);
  if (s.tool != Tool::Resect || !tree || s.resect.clicks.size() < 2 || s.resect_preview.planes.size() < 2 ||
      !s.resect_preview.error.empty()) {
    s.error("A resection needs two cuts that the preview accepts.");
    return;
  }
  const app::ResectPreview& p = s.resect_preview;
  char done[200];
  std::snprintf(done, sizeof done, "Resected %zu faces (%.1f mm2) of '%s'%s", p.removed_faces, p.removed_area,
                obj->name.c_str(), s.resect.anastomosis ? ", the ends sewn together" : "");
  if (s.perform(app::resect_op(obj->name, p.planes, p.reach, s.resect.anastomosis), done)) s.resect.clicks.clear();
}

}  // namespace sutura::ui
