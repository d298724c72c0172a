#include "input_events.hpp"

#include <imgui.h>

#include "sutura/render/glfw_library.hpp"

namespace sutura::ui {

namespace {

InputQueue& queue_of(GLFWwindow* w) { return *static_cast<InputQueue*>(render::glfw().get_window_user_pointer(w)); }

}  // namespace

void InputQueue::attach(GLFWwindow* window) {
  render::glfw().set_window_user_pointer(window, this);
  render::glfw().set_cursor_pos_callback(window, [](GLFWwindow* w, double x, double y) {
    InputEvent e;
    e.kind = InputEvent::Kind::MouseMove;
    e.x = x;
    e.y = y;
    queue_of(w).push(e);
  });
  render::glfw().set_mouse_button_callback(window, [](GLFWwindow* w, int button, int action, int mods) {
    InputEvent e;
    e.kind = InputEvent::Kind::MouseButton;
    e.button = button;
    e.pressed = action == GLFW_PRESS;
    e.mods = mods;
    queue_of(w).push(e);
  });
  render::glfw().set_scroll_callback(window, [](GLFWwindow* w, double dx, double dy) {
    InputEvent e;
    e.kind = InputEvent::Kind::Scroll;
    e.x = dx;
    e.y = dy;
    queue_of(w).push(e);
  });
  render::glfw().set_key_callback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    if (action == GLFW_REPEAT) return;
    InputEvent e;
    e.kind = InputEvent::Kind::Key;
    e.key = key;
    e.pressed = action == GLFW_PRESS;
    e.mods = mods;
    queue_of(w).push(e);
  });
  render::glfw().set_char_callback(window, [](GLFWwindow* w, unsigned c) {
    InputEvent e;
    e.kind = InputEvent::Kind::Char;
    e.codepoint = c;
    queue_of(w).push(e);
  });
}

void InputQueue::feed_imgui() {
  ImGuiIO& io = ImGui::GetIO();
  while (!events_.empty()) {
    const InputEvent e = events_.front();
    events_.pop_front();
    bool transition = false;
    switch (e.kind) {
      case InputEvent::Kind::MouseMove:
        io.MousePos = ImVec2(float(e.x), float(e.y));
        break;
      case InputEvent::Kind::MouseButton:
        if (e.button >= 0 && e.button < 5) io.MouseDown[e.button] = e.pressed;
        transition = true;
        break;
      case InputEvent::Kind::Scroll:
        io.MouseWheelH += float(e.x);
        io.MouseWheel += float(e.y);
        break;
      case InputEvent::Kind::Key:
        if (e.key >= 0 && e.key < IM_ARRAYSIZE(io.KeysDown)) io.KeysDown[e.key] = e.pressed;
        io.KeyCtrl = io.KeysDown[GLFW_KEY_LEFT_CONTROL] || io.KeysDown[GLFW_KEY_RIGHT_CONTROL];
        io.KeyShift = io.KeysDown[GLFW_KEY_LEFT_SHIFT] || io.KeysDown[GLFW_KEY_RIGHT_SHIFT];
        io.KeyAlt = io.KeysDown[GLFW_KEY_LEFT_ALT] || io.KeysDown[GLFW_KEY_RIGHT_ALT];
        io.KeySuper = io.KeysDown[GLFW_KEY_LEFT_SUPER] || io.KeysDown[GLFW_KEY_RIGHT_SUPER];
        transition = true;
        break;
      case InputEvent::Kind::Char:
        io.AddInputCharacter(e.codepoint);
        break;
    }
    if (transition) break;
  }
}

void map_imgui_keys() {
  ImGuiIO& io = ImGui::GetIO();
  io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
  io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
  io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
  io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
  io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
  io.KeyMap[ImGuiKey_PageUp] = GLFW_KEY_PAGE_UP;
  io.KeyMap[ImGuiKey_PageDown] = GLFW_KEY_PAGE_DOWN;
  io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
  io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
  io.KeyMap[ImGuiKey_Insert] = GLFW_KEY_INSERT;
  io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  io.KeyMap[ImGuiKey_KeyPadEnter] = GLFW_KEY_KP_ENTER;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
  io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
  io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
  io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
  io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
}

}  // namespace sutura::ui
