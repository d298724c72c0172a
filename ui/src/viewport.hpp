#pragma once
// The 3-D view: mouse and keys that ImGui does not take (camera, picking, tool clicks,
// shortcuts), and the overlays that show drafts, hover and the cross-section plane.
#include "gui_state.hpp"

namespace sutura::ui {

/// Handles this frame's view input; call between ImGui::NewFrame() and ImGui::Render().
/// `width` x `height` is the size in pixels of the part of the 3-D view the scene is drawn
/// in (left of a colour legend's column); it starts s.view_left pixels from the window's left
/// edge.
void viewport_input(GuiState& s, float width, float height);
/// Drafts (incision points and preview, suture chains), hover highlight, plane marker.
Overlays viewport_overlays(const GuiState& s);

}  // namespace sutura::ui
