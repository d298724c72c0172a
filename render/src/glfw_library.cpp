#include "sutura/render/glfw_library.hpp"

#include "shared_library.hpp"

namespace sutura::render {

GlfwLibrary load_glfw(const std::string& soname) {
  detail::SharedLibrary library(soname, "to open a window", "libglfw3", "GLFW 3.3 or newer");
  GlfwLibrary g;
  library.resolve(g.init, "glfwInit");
  library.resolve(g.terminate, "glfwTerminate");
  library.resolve(g.get_error, "glfwGetError");
  library.resolve(g.default_window_hints, "glfwDefaultWindowHints");
  library.resolve(g.window_hint, "glfwWindowHint");
  library.resolve(g.create_window, "glfwCreateWindow");
  library.resolve(g.destroy_window, "glfwDestroyWindow");
  library.resolve(g.make_context_current, "glfwMakeContextCurrent");
  library.resolve(g.get_proc_address, "glfwGetProcAddress");
  library.resolve(g.swap_buffers, "glfwSwapBuffers");
  library.resolve(g.swap_interval, "glfwSwapInterval");
  library.resolve(g.poll_events, "glfwPollEvents");
  library.resolve(g.wait_events_timeout, "glfwWaitEventsTimeout");
  library.resolve(g.window_should_close, "glfwWindowShouldClose");
  library.resolve(g.set_window_should_close, "glfwSetWindowShouldClose");
  library.resolve(g.set_window_user_pointer, "glfwSetWindowUserPointer");
  library.resolve(g.get_window_user_pointer, "glfwGetWindowUserPointer");
  library.resolve(g.get_window_size, "glfwGetWindowSize");
  library.resolve(g.get_framebuffer_size, "glfwGetFramebufferSize");
  library.resolve(g.create_standard_cursor, "glfwCreateStandardCursor");
  library.resolve(g.destroy_cursor, "glfwDestroyCursor");
  library.resolve(g.set_cursor, "glfwSetCursor");
  library.resolve(g.set_key_callback, "glfwSetKeyCallback");
  library.resolve(g.set_char_callback, "glfwSetCharCallback");
  library.resolve(g.set_mouse_button_callback, "glfwSetMouseButtonCallback");
  library.resolve(g.set_cursor_pos_callback, "glfwSetCursorPosCallback");
  library.resolve(g.set_scroll_callback, "glfwSetScrollCallback");
  return g;
}

const GlfwLibrary& glfw() {
  return detail::load_once<GlfwLibrary>([] { return load_glfw("libglfw.so.3"); });
}

}  // namespace sutura::render
