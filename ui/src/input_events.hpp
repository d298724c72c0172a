#pragma once
// One input path for real and scripted input: GLFW callbacks and the test script both push
// InputEvents into an InputQueue, which feeds them to Dear ImGui's IO once per frame. The
// viewport (camera, picking, tools) reads ImGui's IO afterwards, so a scripted click and a
// real click run exactly the same code.
#include <deque>

struct GLFWwindow;

namespace sutura::ui {

struct InputEvent {
  enum class Kind { MouseMove, MouseButton, Scroll, Key, Char };
  Kind kind = Kind::MouseMove;
  double x = 0.0, y = 0.0;  ///< MouseMove: window pixels (top-left origin); Scroll: offsets
  int button = 0;           ///< MouseButton: 0 left, 1 right, 2 middle
  int key = 0;              ///< Key: GLFW key code
  int mods = 0;             ///< Key: GLFW modifier bits
  bool pressed = false;     ///< MouseButton / Key
  unsigned codepoint = 0;   ///< Char
};

class InputQueue {
 public:
  void push(const InputEvent& e) { events_.push_back(e); }
  /// Installs GLFW callbacks that push the window's events here (the window's user pointer
  /// is set to this queue, which must outlive the window's callbacks).
  void attach(GLFWwindow* window);
  /// Applies queued events to ImGui's IO (ImGui::GetIO()) up to and including the first
  /// button or key transition, so that every press and release is seen by at least one
  /// frame; the rest wait for the next frame. Call before ImGui::NewFrame().
  void feed_imgui();
  [[nodiscard]] bool empty() const { return events_.empty(); }

 private:
  std::deque<InputEvent> events_;
};

/// Sets ImGui's key map to GLFW key codes (ImGuiKey_* -> GLFW_KEY_*). Call once after
/// creating the ImGui context.
void map_imgui_keys();

}  // namespace sutura::ui
