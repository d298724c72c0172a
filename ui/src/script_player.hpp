#pragma once
// Scripted input for tests and benchmarks (`sutura gui --script FILE`): one JSON object per
// line, each a step run on consecutive frames. Pointer and key steps become InputEvents in
// the same queue GLFW fills, so the GUI cannot tell them from a person's input. Steps:
//   {"wait_frames": N}                 let N frames pass
//   {"wait_idle": true}                wait until no action runs (a simulation finished)
//   {"move": [x, y]}                   pointer to window pixel (top-left origin)
//   {"move_world": [x, y, z]}          pointer to where a world point shows now
//   {"click": [x, y]} / {"click_world": [x, y, z]} / {"click_widget": "label"}
//                                      move there, press and release the left button (a
//                                      widget scrolled out of its window is scrolled into view first);
//                                      with "timed": true, prints the time from the release until
//                                      the frame that handled it has been presented
//   {"scroll": N}                      N wheel steps at the pointer (positive: towards)
//   {"key": "enter" | "escape" | "f" | "z" | "y" | "end", "ctrl": bool}   press and release
//   {"type": "text"}                   characters into the focused text field
//   {"screenshot": "file.png"}         save the window as drawn this frame (path as given)
//   {"expect": {"stage": "Plan", "objects": N, "no_errors": true}}   fail if not so
//   {"expect": {"message_contains": "text"}}   fail unless a shown message contains the text
//   {"expect": {"message_not_contains": "text"}}   fail if a shown message contains the text
//   {"expect": {"plan_applied": N, "plan_contains": "text"}}   fail unless N plan steps are in
//       effect and some step's words (app::describe_action) contain the text
//   {"expect": {"min_angle_deg": D}}   fail if a triangle of the shape shown has a smaller
//       angle (app::smallest_angles; wait_idle first)
//   {"expect": {"view": "Superior"}}   fail unless the camera looks from that standard view
//       (to_string(StandardView); "no standard view" after orbiting)
//   {"time_frames": N}                 print the mean frame time of the next N frames
//   {"quit": true}                     as closing the window (asks first when work would be lost)
#include <chrono>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "input_events.hpp"

namespace sutura::ui {

struct GuiState;

/// What a step may look at and ask for.
struct ScriptHost {
  InputQueue& input;
  GuiState& state;
  float view_left = 0.0f;                                 ///< 3-D view's left edge, pixels
  float width = 0.0f, height = 0.0f;                      ///< 3-D view's size, pixels
  std::function<void(const std::filesystem::path&)> screenshot;  ///< after this frame is drawn
};

class ScriptPlayer {
 public:
  /// Reads the script; throws std::runtime_error naming the line of a malformed step.
  explicit ScriptPlayer(const std::filesystem::path& file);
  /// Runs this frame's part of the script. `frame_seconds` is the last frame's duration.
  void step(ScriptHost& host, double frame_seconds);
  [[nodiscard]] bool done() const { return next_ >= steps_.size() || failure_.has_value(); }
  /// The current step waits for the running op to end (wait_idle): frames with nothing new
  /// may be skipped meanwhile, as for a user who watches.
  [[nodiscard]] bool waiting_for_idle() const { return !done() && steps_[next_].contains("wait_idle"); }
  /// Steps not finished yet, the one in progress included.
  [[nodiscard]] std::size_t steps_left() const { return next_ < steps_.size() ? steps_.size() - next_ : 0; }
  [[nodiscard]] const std::optional<std::string>& failure() const { return failure_; }

 private:
  void fail(const std::string& why);
  bool click_at(ScriptHost& host, float x, float y);  // true when the click finished

  std::vector<nlohmann::json> steps_;
  std::size_t next_ = 0;
  int phase_ = 0;          ///< progress within a multi-frame step
  int frames_left_ = 0;
  std::chrono::steady_clock::time_point released_;  ///< when the last click's release was queued
  int scroll_frames_ = 0;  ///< frames spent scrolling a click_widget's widget into view
  static constexpr int kMaxScrollFrames = 5;
  double timed_seconds_ = 0.0;
  std::optional<std::string> failure_;
};

}  // namespace sutura::ui
