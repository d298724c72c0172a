#include "gui_state.hpp"

#include <algorithm>
#include <cmath>

#include "sutura/app/session.hpp"

namespace sutura::ui {

bool GuiState::has_op(const std::string& name) const {
  const auto& ops = app::known_ops();
  return std::find(ops.begin(), ops.end(), name) != ops.end();
}

std::optional<std::string> GuiState::missing_op(const std::string& name) const {
  if (has_op(name)) return std::nullopt;
  return "Not available in this build: the session op '" + name + "' does not exist yet.";
}

std::optional<std::string> GuiState::why_not(Command a, const std::string& op) const {
  if (auto why = stages.why_disabled(a)) return why;
  if (controller.busy() && stages.stage() != Stage::Simulate) return "An action is running.";
  if (!op.empty()) return missing_op(op);
  return std::nullopt;
}

std::vector<std::string> GuiState::unsaved_work() const {
  std::vector<std::string> out;
  if (controller.busy()) out.emplace_back("the simulation running now (its result is not recorded until it finishes)");
  if (!incision.points.empty()) out.emplace_back("the incision being drawn");
  if (!suture.clicks.empty()) out.emplace_back("the suture being picked");
  if (!patch.ends.empty()) out.emplace_back("the patch being placed");
  if (!resect.clicks.empty()) out.emplace_back("the resection being placed");
  if (!remesh.points.empty()) out.emplace_back("the remesh region being drawn");
  if (!fix.clicks.empty()) out.emplace_back("the boundary run being fixed");
  return out;
}

render::Camera GuiState::shown_camera() const {
  render::Camera c = camera.camera();
  if (stages.stage() == Stage::Inspect && side_by_side)
    for (int k = 0; k < 3; ++k) c.eye[k] = c.target[k] + 2.0f * (c.eye[k] - c.target[k]);
  return c;
}

std::optional<render::ClipPlane> GuiState::clip_plane() const {
  if (!cut_open) return std::nullopt;
  const render::Camera c = camera.camera();
  render::Point3 d{c.eye[0] - c.target[0], c.eye[1] - c.target[1], c.eye[2] - c.target[2]};
  const float len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(len > 0.0f)) return std::nullopt;
  render::ClipPlane p;
  for (int k = 0; k < 3; ++k) {
    p.normal[k] = d[k] / len;
    p.point[k] = c.target[k] + cut_offset_mm * p.normal[k];
  }
  return p;
}

bool GuiState::start_run(const nlohmann::json& op, int number, int total, std::string& why) {
  if (!controller.start(op, why)) return false;
  run_started = std::chrono::steady_clock::now();
  run = number;
  runs = total;
  return true;
}

const app::SceneObject* GuiState::selected() const {
  if (controller.busy()) return nullptr;
  const auto& objs = controller.workspace().objects();
  return object < objs.size() ? &objs[object] : nullptr;
}

void GuiState::info(std::string text) {
  messages.push_back({std::move(text), false});
  while (messages.size() > kMessageHistory) messages.pop_front();
  ++messages_posted;
}

void GuiState::error(std::string text) {
  messages.push_back({std::move(text), true, false});
  while (messages.size() > kMessageHistory) messages.pop_front();
  ++messages_posted;
}

void GuiState::warn(std::string text) {
  messages.push_back({std::move(text), true, true});
  while (messages.size() > kMessageHistory) messages.pop_front();
  ++messages_posted;
}

const engine::CentrelineTree* GuiState::selected_centreline() {
  const app::SceneObject* obj = selected();
  if (obj == nullptr) return nullptr;
  if (centreline_revision != controller.workspace_revision() || centreline_object != object) {
    centreline.reset();
    centreline_error.clear();
    try {
      centreline = app::tool_centreline(obj->mesh);
    } catch (const std::exception& e) {
      centreline_error = e.what();
    }
    centreline_revision = controller.workspace_revision();
    centreline_object = object;
  }
  return centreline ? &*centreline : nullptr;
}

void GuiState::show_warning(const nlohmann::json& details) {
  if (details.is_object() && details.contains("warning") && details["warning"].is_string())
    warn(details["warning"].get<std::string>());
}

bool GuiState::perform(const nlohmann::json& op, const std::string& done_text) {
  const ActionOutcome r = controller.run(op);
  if (!r.ok) {
    error(r.op + " failed: " + r.message);
    return false;
  }
  const bool summarised = r.details.is_object() && r.details.contains("summary") && r.details["summary"].is_string();
  info(!done_text.empty() ? done_text : summarised ? r.details["summary"].get<std::string>() : r.op + " done");
  show_warning(r.details);
  if (!stages.has_mesh() && !controller.workspace().objects().empty()) {
    stages.mesh_loaded();
    fit_requested = true;
  }
  return true;
}

}  // namespace sutura::ui
