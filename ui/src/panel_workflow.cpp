// Menu bar, workflow window and message history.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "panels.hpp"

namespace sutura::ui {

void menu_bar(GuiState& s) {
  if (!ImGui::BeginMainMenuBar()) return;
  const bool file_menu = ImGui::BeginMenu("File");
  s.widgets.note("File");
  if (file_menu) {
    ImGui::TextUnformatted("Open session:");
    ImGui::InputText("##open", s.open_session_path, sizeof s.open_session_path);
    s.widgets.note("open session path");
    if (ImGui::MenuItem("Open session")) {
      if (s.open_session_path[0] == '\0') s.error("Open session: type the session file's path first.");
      else s.open_requested = std::filesystem::path(s.open_session_path);
    }
    s.widgets.note("Open session");
    tooltip_for_last_item("Goes on with that session in this window: it is replayed to its last state and "
                          "recorded further in a new file in the output directory; the file itself is "
                          "never written. This session's recording is complete as it is.");
    ImGui::Separator();
    static char target[512] = "session_copy.jsonl";
    ImGui::TextUnformatted("Save session as:");
    ImGui::InputText("##saveas", target, sizeof target);
    if (ImGui::MenuItem("Save session as")) {
      try {
        s.controller.recorder().save_as(target);
        s.info("Session saved as " + std::string(target));
      } catch (const std::exception& e) {
        s.error(e.what());
      }
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit")) s.quit_requested = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Fit view", "F")) s.fit_requested = true;
    for (const StandardView v : kStandardViews)
      if (ImGui::MenuItem(to_string(v))) s.fit_requested = true, s.view_requested = v;
    ImGui::MenuItem("Wireframe", nullptr, &s.wireframe);
    ImGui::MenuItem("Cut open", nullptr, &s.cut_open);
    ImGui::SetNextItemWidth(110.0f);
    ImGui::InputFloat("cut plane, towards you", &s.cut_offset_mm, 0.5f, 2.0f, "%.1f mm");
    s.cut_offset_mm = std::isfinite(s.cut_offset_mm) ? std::clamp(s.cut_offset_mm, -1000.0f, 1000.0f) : 0.0f;
    tooltip_for_last_item("How far the cut plane lies in front of the view's centre (the point the "
                          "view turns about): negative values cut deeper.");
    ImGui::EndMenu();
  }
  // Standard views in the menu bar, outside the 3-D view, so that they never cover the vessel
  // or take a click meant for it (the view cube takes the clicks in its corner square only).
  ImGui::TextDisabled("|  View from:");
  for (const StandardView v : kStandardViews)
    if (gated_button(s.widgets, to_string(v), std::nullopt)) s.fit_requested = true, s.view_requested = v;
  ImGui::Checkbox("Cut open", &s.cut_open);
  s.widgets.note("Cut open");
  tooltip_for_last_item("Cuts away the half of the vessel nearer to you, along a plane facing the view "
                        "through its centre, to look into the lumen; it turns with the view. Cut-away "
                        "parts are not picked, and a saved snapshot is cut the same way (View menu: "
                        "move the plane).");
  ImGui::SameLine(ImGui::GetWindowWidth() - 420.0f);
  ImGui::Text("Stage: %s   |   recording to %s", std::string(to_string(s.stages.stage())).c_str(),
              s.controller.recorder().file().filename().c_str());
  ImGui::EndMainMenuBar();
}

namespace {

enum class LossAnswer { None, Go, Keep };

// The modal that asks before `what` (quitting, opening another session) drops `lost`:
// "`go`" or "Keep planning"; the answer of this frame (None while it waits).
LossAnswer confirm_loss(GuiState& s, const char* title, const char* what, const char* go,
                        const std::vector<std::string>& lost) {
  if (!ImGui::IsPopupOpen(title)) ImGui::OpenPopup(title);
  LossAnswer answer = LossAnswer::None;
  if (ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::Text("Every committed action is in the recording. %s now loses:", what);
    for (const auto& l : lost) ImGui::BulletText("%s", l.c_str());
    if (gated_button(s.widgets, go, std::nullopt)) answer = LossAnswer::Go;
    ImGui::SameLine();
    if (gated_button(s.widgets, "Keep planning", std::nullopt)) answer = LossAnswer::Keep;
    if (answer != LossAnswer::None) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  return answer;
}

}  // namespace

void open_dialog(GuiState& s) {
  if (!s.open_requested || s.open_confirmed) return;
  const std::vector<std::string> lost = s.unsaved_work();
  const LossAnswer answer =
      lost.empty() ? LossAnswer::Go : confirm_loss(s, "Open another session?", "Opening", "Open anyway", lost);
  if (answer == LossAnswer::Go) s.open_confirmed = true;
  if (answer == LossAnswer::Keep) s.open_requested.reset();
}

void quit_dialog(GuiState& s) {
  if (!s.quit_requested) return;
  const std::vector<std::string> lost = s.unsaved_work();
  const LossAnswer answer = lost.empty() ? LossAnswer::Go : confirm_loss(s, "Quit Sutura?", "Quitting", "Quit anyway", lost);
  if (answer == LossAnswer::Go) s.quit = true;
  if (answer == LossAnswer::Keep) s.quit_requested = false;
}

void workflow_window(GuiState& s) {
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  // Below the main menu bar (WorkPos only accounts for it from the second frame on).
  const float top = vp->Pos.y + ImGui::GetFrameHeight() + 6.0f;
  ImGui::SetNextWindowPos(ImVec2(vp->Pos.x + 6, top), ImGuiCond_Once);
  ImGui::SetNextWindowSize(ImVec2(390, vp->Pos.y + vp->Size.y - top - 96), ImGuiCond_Once);
  ImGui::Begin("Sutura");
  static Stage shown = Stage::Inspect;  // the section of the current stage opens on changes
  const Stage now = s.stages.stage();
  const auto header = [&](const char* title, Stage stage) {
    if (shown != now) ImGui::SetNextItemOpen(stage == now);
    const bool open = ImGui::CollapsingHeader(title);
    s.widgets.note(title);
    return open;
  };
  if (header("Plan", Stage::Plan)) plan_section(s);
  if (header("Simulate", Stage::Simulate)) simulate_section(s);
  if (header("Inspect", Stage::Inspect)) inspect_section(s);
  shown = now;
  s.view_left = ImGui::GetWindowPos().x + ImGui::GetWindowWidth() + 2.0f;
  ImGui::End();
}

void message_window(GuiState& s) {
  if (s.messages.empty()) return;
  const ImGuiViewport* vp = ImGui::GetMainViewport();
  // Anchored to the bottom edge, right of the workflow window, across the view; the user makes
  // it taller by dragging its top edge (up to 60 % of the window) and scrolls back through the
  // history.
  const float width = vp->WorkSize.x - 408;
  ImGui::SetNextWindowPos(ImVec2(vp->WorkPos.x + 402, vp->WorkPos.y + vp->WorkSize.y - 6),
                          ImGuiCond_Always, ImVec2(0.0f, 1.0f));
  s.message_height = std::clamp(s.message_height, 80.0f, std::max(80.0f, 0.6f * vp->WorkSize.y));
  ImGui::SetNextWindowSize(ImVec2(width, s.message_height), ImGuiCond_Always);
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 80),
                                      ImVec2(width, std::max(80.0f, 0.6f * vp->WorkSize.y)));
  ImGui::Begin("Messages", nullptr, ImGuiWindowFlags_NoCollapse);
  s.message_height = ImGui::GetWindowHeight();  // as the user's drag of its edge left it
  ImGui::BeginChild("history", ImVec2(0.0f, -ImGui::GetFrameHeightWithSpacing()));
  // Follow new messages only when the history was scrolled to its end (one reading back keeps
  // its place).
  const bool at_end = ImGui::GetScrollY() >= ImGui::GetScrollMaxY() - 1.0f;
  for (const auto& m : s.messages) {
    if (m.error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.1f, 0.1f, 1.0f));
    ImGui::TextWrapped("%s%s", m.warning ? "Warning: " : m.error ? "Error: " : "", m.text.c_str());
    if (m.error) ImGui::PopStyleColor();
  }
  if (s.messages_posted != s.messages_shown && at_end) ImGui::SetScrollHereY(1.0f);
  s.messages_shown = s.messages_posted;
  ImGui::EndChild();
  if (ImGui::Button("Clear messages")) s.messages.clear();
  s.widgets.note("Clear messages");
  ImGui::End();
}

}  // namespace sutura::ui
