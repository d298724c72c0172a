#include "widgets.hpp"

#include <algorithm>

namespace sutura::ui {

void WidgetRegistry::note(const std::string& label) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  const ImVec2 c(0.5f * (a.x + b.x), 0.5f * (a.y + b.y));
  const ImVec2 lo = ImGui::GetWindowDrawList()->GetClipRectMin(), hi = ImGui::GetWindowDrawList()->GetClipRectMax();
  const bool visible = c.x >= lo.x && c.x <= hi.x && c.y >= lo.y && c.y <= hi.y;
  current_[label] = {ImVec4(a.x, a.y, b.x, b.y), visible};
  if (!visible && label == scroll_to_) ImGui::SetScrollHereY(0.5f);
  if (label == scroll_to_) scroll_to_.clear();
}

void WidgetRegistry::note_rect(const std::string& label, const ImVec4& rect) {
  current_[label] = {rect, true};
}

std::optional<ImVec2> WidgetRegistry::centre(const std::string& label) const {
  for (const auto* map : {&current_, &previous_}) {
    const auto it = map->find(label);
    if (it != map->end()) {
      const ImVec4& r = it->second.rect;
      return ImVec2(0.5f * (r.x + r.z), 0.5f * (r.y + r.w));
    }
  }
  return std::nullopt;
}

bool WidgetRegistry::visible(const std::string& label) const {
  for (const auto* map : {&current_, &previous_}) {
    const auto it = map->find(label);
    if (it != map->end()) return it->second.visible;
  }
  return false;
}

void WidgetRegistry::new_frame() {
  previous_ = std::move(current_);
  current_.clear();
}

void tooltip_for_last_item(const std::string& text) {
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

bool gated_button(WidgetRegistry& widgets, const std::string& label,
                  const std::optional<std::string>& why_not, const char* tooltip) {
  ImGui::BeginDisabled(why_not.has_value());
  const bool clicked = ImGui::Button(label.c_str());
  ImGui::EndDisabled();
  widgets.note(label);
  if (why_not) tooltip_for_last_item(*why_not);
  else if (tooltip != nullptr) tooltip_for_last_item(tooltip);
  return clicked && !why_not;
}

bool noted_checkbox(WidgetRegistry& widgets, const std::string& label, bool* value) {
  const bool changed = ImGui::Checkbox(label.c_str(), value);
  widgets.note(label);
  return changed;
}

bool noted_radio(WidgetRegistry& widgets, const std::string& label, bool active) {
  const bool clicked = ImGui::RadioButton(label.c_str(), active);
  widgets.note(label);
  return clicked;
}

bool noted_tree_node(WidgetRegistry& widgets, const std::string& label) {
  const bool open = ImGui::TreeNode(label.c_str());
  widgets.note(label);
  return open;
}

bool number_field(const char* label, float* value, float lo, float hi, float step, const char* format) {
  const float before = *value;
  ImGui::InputFloat(label, value, step, 10.0f * step, format);
  *value = std::clamp(*value, lo, hi);
  return *value != before;
}

bool number_field(const char* label, int* value, int lo, int hi) {
  const int before = *value;
  ImGui::InputInt(label, value);
  *value = std::clamp(*value, lo, hi);
  return *value != before;
}

}  // namespace sutura::ui
