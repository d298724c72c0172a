// The plan list: the steps of the plan in words (app::describe_action), undone ones greyed,
// and the selected step inspected (status, note, the action as recorded, what it did).
#include <algorithm>
#include <string>

#include "panels.hpp"
#include "sutura/app/plan.hpp"

namespace sutura::ui {

namespace {

// JSON for reading in the panel, cut at `limit` characters (a long incision's points, a
// run's report) with the number of characters left out.
std::string readable(const nlohmann::json& j, std::size_t limit = 1200) {
  std::string text = j.dump(1);
  if (text.size() > limit) text = text.substr(0, limit) + "\n… (" + std::to_string(text.size() - limit) + " more characters)";
  return text;
}

void inspect_step(GuiState& s, std::size_t i) {
  const app::Plan& p = s.plan;
  const app::PlanStep& step = p.steps[i];
  ImGui::Text("Step %zu: line %d of %s", i + 1, step.line,
              s.controller.recorder().file().filename().string().c_str());
  const bool undone = i >= p.applied;
  const bool reachable = i + p.undoable >= p.applied;  // among the last `undoable` applied
  ImGui::TextWrapped("%s", undone      ? "Undone: Redo brings the undone steps back, oldest first."
                           : reachable ? "In effect."
                                       : "In effect; older than the undo history holds.");
  if (step.source.contains("note") && step.source["note"].is_string())
    ImGui::TextWrapped("Note: %s", step.source["note"].get<std::string>().c_str());
  if (!undone && i + 1 == p.applied && p.undoable > 0) {
    if (gated_button(s.widgets, "Undo this step", s.why_not(Command::Undo, "undo"))) undo(s);
  } else if (undone && i == p.applied) {
    if (gated_button(s.widgets, "Redo this step", s.why_not(Command::Redo, "redo"))) redo(s);
  }
  if (step.result.contains("seconds") && step.result["seconds"].is_number() &&
      step.result["seconds"].get<double>() >= 0.01)
    ImGui::Text("Took %.2f s.", step.result["seconds"].get<double>());
  if (step.result.contains("warning") && step.result["warning"].is_string())
    ImGui::TextWrapped("Warning: %s", step.result["warning"].get<std::string>().c_str());
  if (noted_tree_node(s.widgets, "As recorded")) {
    ImGui::TextWrapped("%s", readable(step.source).c_str());
    ImGui::TreePop();
  }
  nlohmann::json result = step.result;
  for (const char* key : {"line", "op", "seconds", "warning"}) result.erase(key);
  if (!result.empty() && ImGui::TreeNode("What it did")) {
    ImGui::TextWrapped("%s", readable(result).c_str());
    ImGui::TreePop();
  }
}

}  // namespace

void plan_steps(GuiState& s) {
  if (s.controller.busy()) {
    ImGui::TextDisabled("The plan list returns when the run has ended.");
    return;
  }
  if (s.plan_revision != s.controller.revision()) {
    // The selection follows its step (by its line in the recording); a step replaced by a
    // new one after undo is no longer there to inspect.
    const int line = s.plan_selected >= 0 ? s.plan.steps[static_cast<std::size_t>(s.plan_selected)].line : -1;
    s.plan = s.controller.plan();
    s.plan_revision = s.controller.revision();
    s.plan_selected = -1;
    for (std::size_t i = 0; i < s.plan.steps.size() && line >= 0; ++i)
      if (s.plan.steps[i].line == line) s.plan_selected = static_cast<int>(i);
  }
  const app::Plan& p = s.plan;
  if (p.steps.empty()) {
    ImGui::TextDisabled("Nothing planned yet: each change to the objects becomes a step.");
    return;
  }
  const float rows = static_cast<float>(std::min<std::size_t>(p.steps.size(), 8));
  ImGui::BeginChild("plan list", ImVec2(0.0f, rows * ImGui::GetTextLineHeightWithSpacing() +
                                                   2.0f * ImGui::GetStyle().WindowPadding.y + 2.0f),
                    true);
  for (std::size_t i = 0; i < p.steps.size(); ++i) {
    const bool undone = i >= p.applied;
    const std::string text = std::to_string(i + 1) + ". " + app::describe_action(p.steps[i].source);
    if (undone) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    const std::string label = text + (undone ? "  (undone)" : "") + "##step" + std::to_string(i);
    if (ImGui::Selectable(label.c_str(), s.plan_selected == static_cast<int>(i)))
      s.plan_selected = s.plan_selected == static_cast<int>(i) ? -1 : static_cast<int>(i);
    if (undone) ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text.c_str());
    s.widgets.note("plan step " + std::to_string(i + 1));
  }
  // A new step scrolls into view, as the message history does.
  if (p.steps.size() != s.plan_steps_shown) ImGui::SetScrollHereY(1.0f);
  s.plan_steps_shown = p.steps.size();
  ImGui::EndChild();
  if (s.plan_selected >= 0) inspect_step(s, static_cast<std::size_t>(s.plan_selected));
}

}  // namespace sutura::ui
