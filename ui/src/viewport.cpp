#include "viewport.hpp"

#include <GLFW/glfw3.h>

#include "panels.hpp"
#include "sutura/app/suture_preview.hpp"

namespace sutura::ui {

namespace {

// A boundary corner within this many pixels of the cursor is what a click takes, and an
// incision point this close to an open boundary goes onto it.
constexpr double kCornerSnapPx = 10.0;

render::Point3 point(const engine::Vec3& p) { return {float(p.x()), float(p.y()), float(p.z())}; }

// Fixes the boundary run between the two clicks of the fix draft.
void fix_run(GuiState& s, const app::SceneObject& obj) {
  const std::array<engine::Vec3, 2> ends{s.fix.clicks[0], s.fix.clicks[1]};
  s.fix.clicks.clear();
  try {
    const nlohmann::json op = app::fix_run_op(obj.mesh, obj.name, ends[0], ends[1], s.has_op("fix"));
    const std::size_t n = op.at("vertices").size();
    s.perform(op, "Fixed " + std::to_string(n) + " boundary vertices of '" + obj.name + "'");
  } catch (const std::exception& e) {
    s.error(std::string("Fix ends: ") + e.what());
  }
}

// A click in the view with the current tool; `snap_angle` is the angle kCornerSnapPx subtend.
void click(GuiState& s, double snap_angle) {
  if (!s.hover) return;
  const Pick& h = *s.hover;
  if (s.stages.stage() == Stage::Inspect) {
    s.object = h.object;
    s.plane_origin = h.hit.point;
    return;
  }
  if (s.stages.stage() != Stage::Plan) return;
  const auto* obj = s.selected();
  if (h.object != s.object) {
    s.object = h.object;  // first click on another object selects it
    cancel_draft(s);
    return;
  }
  const engine::Vec3 on_boundary =
      h.boundary_vertex.valid() && obj ? obj->mesh.position(h.boundary_vertex) : h.hit.point;
  switch (s.tool) {
    case Tool::Navigate: break;
    case Tool::Incise: {
      // Within a few pixels of an open boundary (a vessel end, a cut edge), the incision
      // starts or ends on it.
      engine::Vec3 p = h.hit.point;
      if (h.boundary_vertex.valid() && obj &&
          (obj->mesh.position(h.boundary_vertex) - p).norm() <= h.hit.t * std::tan(snap_angle))
        p = obj->mesh.position(h.boundary_vertex);
      s.incision.points.push_back(p);
      break;
    }
    case Tool::Remesh: s.remesh.points.push_back(h.hit.point); break;
    case Tool::Resect:
      if (s.resect.clicks.size() == 2) s.resect.clicks.clear();  // a third click starts again
      s.resect.clicks.push_back(h.hit.point);
      break;
    case Tool::Suture:
      if (s.suture.clicks.size() < 4) s.suture.clicks.push_back(on_boundary);
      break;
    case Tool::Patch:
      if (s.patch.ends.size() < 2) s.patch.ends.push_back(on_boundary);
      break;
    case Tool::Fix:
      if (h.boundary_loop < 0 || !obj) {
        s.error("Fix ends: click closer to a boundary loop (a vessel end or a lip).");
        break;
      }
      if (!s.fix.run) {
      {
        const std::string end = app::end_name(*obj, obj->mesh.boundary_loops()[std::size_t(h.boundary_loop)]);
        s.perform(app::fix_loop_op(obj->name, h.boundary_loop, s.has_op("fix")),
                  "Fixed boundary loop " + std::to_string(h.boundary_loop) + " of '" + obj->name + "'" +
                      (end.empty() ? "" : " (" + end + ")"));
      }
        break;
      }
      s.fix.clicks.push_back(on_boundary);
      if (s.fix.clicks.size() == 2) fix_run(s, *obj);
      break;
  }
}

void shortcuts(GuiState& s) {
  const ImGuiIO& io = ImGui::GetIO();
  if (ImGui::IsKeyPressed(GLFW_KEY_F, false) && !io.KeyCtrl) s.fit_requested = true;
  if (s.stages.stage() == Stage::Plan && !s.controller.busy()) {
    if (ImGui::IsKeyPressed(GLFW_KEY_ENTER, false) || ImGui::IsKeyPressed(GLFW_KEY_KP_ENTER, false)) {
      if (s.tool == Tool::Incise) commit_incision(s);
      else if (s.tool == Tool::Suture) commit_suture(s);
      else if (s.tool == Tool::Resect) commit_resection(s);
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) cancel_draft(s);
  }
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false)) undo(s);
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false)) redo(s);
}

}  // namespace

void viewport_input(GuiState& s, float width, float height) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) shortcuts(s);
  s.hover.reset();
  if (io.WantCaptureMouse) return;
  // Picking needs a mesh that matches the picker (not during a run, not in split views).
  const bool can_pick = !s.controller.busy() && !s.side_by_side && !s.show_before &&
                        s.picker_revision == s.controller.revision();
  const double snap_angle = kCornerSnapPx * s.camera.radians_per_pixel(height);
  if (can_pick && ImGui::IsMousePosValid() && io.MousePos.x - s.view_left < width) {  // not over the legend
    const engine::Ray ray = s.camera.ray_through(io.MousePos.x - s.view_left, io.MousePos.y, width, height);
    const std::array<double, 2> uncut = uncut_part(ray, s.clip_plane());  // nothing cut away is picked
    s.hover = s.picker.pick(ray, snap_angle, uncut[0], uncut[1]);
  }
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) s.camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
  if (ImGui::IsMouseDragging(ImGuiMouseButton_Right) || ImGui::IsMouseDragging(ImGuiMouseButton_Middle))
    s.camera.pan(io.MouseDelta.x, io.MouseDelta.y, height);
  if (io.MouseWheel != 0.0f) {
    if (s.hover) s.camera.zoom_towards(s.hover->hit.point, io.MouseWheel);  // zoom to the cursor
    else s.camera.zoom(io.MouseWheel);
  }
  // A click is a press and release without dragging.
  if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && io.MouseDragMaxDistanceSqr[0] < 16.0f) click(s, snap_angle);
}

Overlays viewport_overlays(const GuiState& s) {
  Overlays o;
  const auto line = [&](const std::vector<engine::Vec3>& pts, render::Color c, float w) {
    render::PolylineItem l;
    for (const auto& p : pts) l.points.push_back(point(p));
    l.color = c;
    l.width_px = w;
    o.lines.push_back(std::move(l));
  };
  const auto markers = [&](const std::vector<engine::Vec3>& pts, render::Color c, float size) {
    render::PointsItem m;
    for (const auto& p : pts) m.points.push_back(point(p));
    m.color = c;
    m.size_px = size;
    o.points.push_back(std::move(m));
  };
  const app::SceneObject* obj = s.selected();
  if (s.stages.stage() == Stage::Plan) {
    if (s.tool == Tool::Incise && !s.incision.points.empty()) {
      std::vector<engine::Vec3> preview = s.incision.points;
      if (s.hover && s.hover->object == s.object) preview.push_back(s.hover->hit.point);
      line(preview, {0.85f, 0.05f, 0.05f}, 3.0f);
      markers(s.incision.points, {0.85f, 0.05f, 0.05f}, 9.0f);
    }
    if (s.tool == Tool::Suture && obj) {
      const app::SuturePreview p = app::preview_suture(obj->mesh, s.suture.clicks, s.suture.long_way, s.suture.lip_to_lip);
      const render::Color colors[2] = {{0.05f, 0.55f, 0.15f}, {0.55f, 0.1f, 0.7f}};
      for (std::size_t i = 0; i < p.chains.size(); ++i) line(p.chains[i], colors[i], 5.0f);
      for (const auto& ends : p.meeting_ends) line({ends[0], ends[1]}, {0.35f, 0.35f, 0.35f}, 2.5f);
      markers(s.suture.clicks, {0.05f, 0.35f, 0.1f}, 10.0f);
    }
    if (s.tool == Tool::Patch) {
      // The preview is brought up to date by the panel, drawn before the view.
      if (s.patch.ends.size() == 2 && !s.patch_preview.outline.empty() &&
          s.patch_preview_revision == s.controller.revision())  // not one of an older mesh
        line(s.patch_preview.outline, {0.1f, 0.3f, 0.9f}, 3.0f);
      markers(s.patch.ends, {0.1f, 0.3f, 0.9f}, 10.0f);
    }
    if (s.tool == Tool::Remesh) markers(s.remesh.points, {0.6f, 0.2f, 0.8f}, 10.0f);
    if (s.tool == Tool::Resect && !s.resect.clicks.empty()) {
      // The preview is brought up to date by the panel, drawn before the view.
      const app::ResectPreview& p = s.resect_preview;
      for (std::size_t k = 0; k < p.planes.size(); ++k) {
        const engine::Vec3 n = p.planes[k].normal.normalized();
        const engine::Vec3 u = n.unitOrthogonal(), v = n.cross(u);
        const double r = 1.3 * p.cuts[k].wall_distance;
        std::vector<engine::Vec3> circle;
        for (int i = 0; i <= 48; ++i) {
          const double a = 2.0 * M_PI * i / 48.0;
          circle.push_back(p.planes[k].origin + r * (std::cos(a) * u + std::sin(a) * v));
        }
        line(circle, {0.1f, 0.4f, 0.9f}, 2.5f);
      }
      for (const auto& loop : p.loops) {
        std::vector<engine::Vec3> closed = loop;
        if (!closed.empty()) closed.push_back(closed.front());
        line(closed, {0.85f, 0.05f, 0.05f}, 4.0f);
      }
      markers(p.removed, {0.85f, 0.1f, 0.1f}, 5.0f);
      markers(s.resect.clicks, {0.1f, 0.4f, 0.9f}, 10.0f);
    }
    if (s.tool == Tool::Fix) markers(s.fix.clicks, {0.95f, 0.75f, 0.05f}, 12.0f);
    // Hovered boundary loop: what a Fix or Suture click would take.
    if (s.hover && s.hover->boundary_loop >= 0 && obj && s.hover->object == s.object &&
        (s.tool == Tool::Fix || s.tool == Tool::Suture || s.tool == Tool::Patch)) {
      const auto loops = obj->mesh.boundary_loops();
      std::vector<engine::Vec3> pts;
      for (auto v : loops[static_cast<std::size_t>(s.hover->boundary_loop)]) pts.push_back(obj->mesh.position(v));
      pts.push_back(pts.front());
      line(pts, {1.0f, 0.55f, 0.0f}, 5.0f);
      markers({obj->mesh.position(s.hover->boundary_vertex)}, {1.0f, 0.55f, 0.0f}, 12.0f);
    }
  }
  if (s.stages.stage() != Stage::Inspect && !s.controller.busy()) {
    for (const auto& t : s.element_check.refused) markers(t.where, {0.9f, 0.05f, 0.05f}, 9.0f);
    for (const auto& t : s.element_check.warned) markers(t.where, {1.0f, 0.55f, 0.0f}, 7.0f);
  }
  if (s.hover) markers({s.hover->hit.point}, {0.05f, 0.05f, 0.05f}, 8.0f);
  if (s.stages.stage() == Stage::Inspect && s.section_controls_open && obj) {
    // The plane as a square outline around its origin (brought up to date by the panel), and
    // the last measured section's outline now.
    if (s.section_plane) {
      const double r = s.section_extent;
      const engine::Vec3 n = s.section_plane->normal.normalized();
      const engine::Vec3 u = n.unitOrthogonal(), v = n.cross(u);
      const engine::Vec3& c = s.section_plane->origin;
      line({c + r * (u + v), c + r * (u - v), c - r * (u + v), c - r * (u - v), c + r * (u + v)},
           {0.1f, 0.4f, 0.9f}, 2.5f);
      markers({c}, {0.1f, 0.4f, 0.9f}, 10.0f);
    }
    if (s.last_section && !s.last_section->after.points.empty()) {
      std::vector<engine::Vec3> outline = s.last_section->after.points;
      if (s.last_section->after.closed) outline.push_back(outline.front());
      line(outline, {0.9f, 0.47f, 0.08f}, 3.0f);
    }
  }
  return o;
}

}  // namespace sutura::ui
