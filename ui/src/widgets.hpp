#pragma once
// Small ImGui helpers shared by the panels: buttons gated by a reason (disabled, with the
// reason as tooltip), and a registry of where each labelled widget was drawn last frame,
// which the test script uses to move the pointer onto a widget by its label.
#include <map>
#include <optional>
#include <string>

#include <imgui.h>

namespace sutura::ui {

class WidgetRegistry {
 public:
  /// Records the last ImGui item's rectangle under `label`.
  void note(const std::string& label);
  /// Records `rect` (min x, min y, max x, max y; window pixels) under `label`: a part of an
  /// item that is clicked by place, such as a face of the view cube.
  void note_rect(const std::string& label, const ImVec4& rect);
  /// Centre of the widget drawn with `label` in the last frame, if any.
  [[nodiscard]] std::optional<ImVec2> centre(const std::string& label) const;
  /// The centre of that widget was inside its window's visible area (not scrolled away).
  [[nodiscard]] bool visible(const std::string& label) const;
  /// The next time `label` is drawn scrolled out of view, its window scrolls to it (as a
  /// user scrolls to a button below the fold before clicking it).
  void scroll_into_view(const std::string& label) { scroll_to_ = label; }
  /// Forgets widgets not drawn since the previous call (call once per frame, before drawing).
  void new_frame();

 private:
  struct Drawn {
    ImVec4 rect;   ///< min x, min y, max x, max y
    bool visible;  ///< the centre lay within the window's clip rectangle
  };
  std::map<std::string, Drawn> current_, previous_;
  std::string scroll_to_;
};

/// A button that is disabled when `why_not` holds a reason, which then shows as its tooltip
/// (also `tooltip` when enabled, if given). Returns true when clicked.
bool gated_button(WidgetRegistry& widgets, const std::string& label,
                  const std::optional<std::string>& why_not, const char* tooltip = nullptr);
/// Checkbox / radio button / menu item that also records its rectangle.
bool noted_checkbox(WidgetRegistry& widgets, const std::string& label, bool* value);
bool noted_radio(WidgetRegistry& widgets, const std::string& label, bool active);
/// ImGui::TreeNode that records its rectangle; true when open (then call ImGui::TreePop()).
bool noted_tree_node(WidgetRegistry& widgets, const std::string& label);
/// A number typed in (or stepped with the - and + buttons by `step`), with its unit in the
/// label, kept within [lo, hi]: unlike a slider, a click does not set it to where the pointer
/// is. Returns true when the value changed.
bool number_field(const char* label, float* value, float lo, float hi, float step,
                  const char* format = "%.2f");
bool number_field(const char* label, int* value, int lo, int hi);
/// Shows `text` as tooltip of the last item when hovered, also when it is disabled.
void tooltip_for_last_item(const std::string& text);

}  // namespace sutura::ui
