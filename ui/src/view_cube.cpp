// The view cube: orientation at a glance, and one click to a standard view.
#include <algorithm>
#include <array>
#include <cmath>

#include "panels.hpp"

namespace sutura::ui {

namespace {

using engine::Vec3;

struct CubeFace {
  StandardView view;
  Vec3 normal;  ///< outward, in the patient frame: the eye of `view` lies along it
  const char* letter;
};

// +x patient's left, +y posterior, +z superior (docs/anatomy.md).
const std::array<CubeFace, 6> kFaces{{
    {StandardView::Anterior, Vec3(0, -1, 0), "A"},
    {StandardView::Posterior, Vec3(0, 1, 0), "P"},
    {StandardView::LeftLateral, Vec3(1, 0, 0), "L"},
    {StandardView::RightLateral, Vec3(-1, 0, 0), "R"},
    {StandardView::Superior, Vec3(0, 0, 1), "S"},
    {StandardView::Inferior, Vec3(0, 0, -1), "I"},
}};

bool inside(const std::array<ImVec2, 4>& quad, ImVec2 p) {
  int sign = 0;
  for (int k = 0; k < 4; ++k) {
    const ImVec2 a = quad[k], b = quad[(k + 1) % 4];
    const float cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    const int s = cross > 0.0f ? 1 : cross < 0.0f ? -1 : 0;
    if (s != 0 && sign != 0 && s != sign) return false;
    if (s != 0) sign = s;
  }
  return true;
}

}  // namespace

void view_cube(GuiState& s) {
  constexpr float kMargin = 8.0f;
  const float size = kViewCubeCorner - 2.0f * kMargin;
  ImGui::SetNextWindowPos(ImVec2(s.view_left + kMargin, ImGui::GetFrameHeight() + kMargin));
  ImGui::SetNextWindowSize(ImVec2(size, size));
  ImGui::SetNextWindowBgAlpha(0.0f);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0.0f, 0.0f));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
  const bool open = ImGui::Begin("##view cube", nullptr,
                                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoNav |
                                     ImGuiWindowFlags_NoFocusOnAppearing |
                                     ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::PopStyleVar(2);
  if (!open) {
    ImGui::End();
    return;
  }
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("view cube", ImVec2(size, size));
  const bool hovered = ImGui::IsItemHovered(), clicked = ImGui::IsItemClicked(ImGuiMouseButton_Left);
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const ImVec2 centre(corner.x + 0.5f * size, corner.y + 0.5f * size);
  // A unit half-edge projects to at most sqrt(3) of this: the cube stays inside its square.
  const float scale = 0.28f * size;
  // Named copies, not a structured binding: a lambda may not capture one before C++20 as
  // clang 14 (the sanitized build) implements it.
  const std::array<Vec3, 3> axes = s.camera.view_axes();
  const Vec3 right = axes[0], up = axes[1], forward = axes[2];
  const auto on_screen = [&](const Vec3& p) {
    return ImVec2(centre.x + scale * float(p.dot(right)), centre.y - scale * float(p.dot(up)));
  };
  const std::optional<StandardView> current = s.camera.standard_view();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  std::optional<StandardView> under_pointer;
  for (const CubeFace& face : kFaces) {
    const double facing = -face.normal.dot(forward);  // 1: seen head on
    if (facing <= 1e-3) continue;                      // turned away: hidden behind the others
    // Two edge directions of the face: the other two axes.
    const Vec3 t1 = face.normal.cross(std::abs(face.normal.z()) > 0.5 ? Vec3::UnitX() : Vec3::UnitZ());
    const Vec3 t2 = face.normal.cross(t1);
    const std::array<ImVec2, 4> quad{on_screen(face.normal - t1 - t2), on_screen(face.normal + t1 - t2),
                                     on_screen(face.normal + t1 + t2), on_screen(face.normal - t1 + t2)};
    const bool pointed = hovered && inside(quad, mouse);
    if (pointed) under_pointer = face.view;
    const int shade = 150 + int(90.0 * facing);
    const ImU32 fill = pointed                   ? IM_COL32(120, 170, 230, 235)
                       : current == face.view ? IM_COL32(190, 215, 245, 235)
                                              : IM_COL32(shade, shade, shade, 225);
    draw->AddConvexPolyFilled(quad.data(), 4, fill);
    draw->AddPolyline(quad.data(), 4, IM_COL32(70, 70, 80, 255), ImDrawFlags_Closed, 1.0f);
    const ImVec2 mid = on_screen(face.normal);
    if (facing > 0.3) {
      const ImVec2 text = ImGui::CalcTextSize(face.letter);
      draw->AddText(ImVec2(mid.x - 0.5f * text.x, mid.y - 0.5f * text.y), IM_COL32(30, 30, 40, 255), face.letter);
    }
    // A face seen obliquely is clicked by the test script at its centre, which is inside it.
    if (facing > 0.2) {
      ImVec4 box(mid.x, mid.y, mid.x, mid.y);
      for (const ImVec2& c : quad)
        box = ImVec4(std::min(box.x, c.x), std::min(box.y, c.y), std::max(box.z, c.x), std::max(box.w, c.y));
      s.widgets.note_rect("view cube " + std::string(to_string(face.view)), box);
    }
  }
  if (under_pointer) {
    ImGui::SetTooltip("View from: %s", to_string(*under_pointer));
    if (clicked) s.fit_requested = true, s.view_requested = under_pointer;
  }
  ImGui::End();
}

}  // namespace sutura::ui
