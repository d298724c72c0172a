#pragma once
// GLFW, loaded when the first window is opened, not when the program starts.
//
// Why: a replay, a snapshot or `sutura --version` never opens a window, and linking GLFW made
// every start load it with X11 and xcb (seven libraries, their relocations and constructors);
// a headless machine without them could not run the program at all. dlopen defers it to the
// first window (`sutura gui`); a machine without the library can still replay, and the window
// fails with a message that names the package. The symbols are resolved once, process-wide.
// Only GLFW's header is needed to build (types and constants; the functions come from here).
#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE  // no GL header: GL calls go through the renderer's GlApi
#endif
#include <GLFW/glfw3.h>

#include <string>

namespace sutura::render {

/// The GLFW entry points the window and its input use, named as GLFW's without the prefix.
struct GlfwLibrary {
  decltype(&::glfwInit) init = nullptr;
  decltype(&::glfwTerminate) terminate = nullptr;
  decltype(&::glfwGetError) get_error = nullptr;
  decltype(&::glfwDefaultWindowHints) default_window_hints = nullptr;
  decltype(&::glfwWindowHint) window_hint = nullptr;
  decltype(&::glfwCreateWindow) create_window = nullptr;
  decltype(&::glfwDestroyWindow) destroy_window = nullptr;
  decltype(&::glfwMakeContextCurrent) make_context_current = nullptr;
  decltype(&::glfwGetProcAddress) get_proc_address = nullptr;
  decltype(&::glfwSwapBuffers) swap_buffers = nullptr;
  decltype(&::glfwSwapInterval) swap_interval = nullptr;
  decltype(&::glfwPollEvents) poll_events = nullptr;
  decltype(&::glfwWaitEventsTimeout) wait_events_timeout = nullptr;
  decltype(&::glfwWindowShouldClose) window_should_close = nullptr;
  decltype(&::glfwSetWindowShouldClose) set_window_should_close = nullptr;
  decltype(&::glfwSetWindowUserPointer) set_window_user_pointer = nullptr;
  decltype(&::glfwGetWindowUserPointer) get_window_user_pointer = nullptr;
  decltype(&::glfwGetWindowSize) get_window_size = nullptr;
  decltype(&::glfwGetFramebufferSize) get_framebuffer_size = nullptr;
  decltype(&::glfwCreateStandardCursor) create_standard_cursor = nullptr;
  decltype(&::glfwDestroyCursor) destroy_cursor = nullptr;
  decltype(&::glfwSetCursor) set_cursor = nullptr;
  decltype(&::glfwSetKeyCallback) set_key_callback = nullptr;
  decltype(&::glfwSetCharCallback) set_char_callback = nullptr;
  decltype(&::glfwSetMouseButtonCallback) set_mouse_button_callback = nullptr;
  decltype(&::glfwSetCursorPosCallback) set_cursor_pos_callback = nullptr;
  decltype(&::glfwSetScrollCallback) set_scroll_callback = nullptr;
};

/// Loads `soname` (RTLD_NOW | RTLD_LOCAL) and resolves the entry points. Throws GlError naming
/// the library, the Debian package (libglfw3) and dlerror() when it cannot. Never unloaded.
GlfwLibrary load_glfw(const std::string& soname);

/// load_glfw("libglfw.so.3"), once per process (thread-safe); a failure is thrown again on
/// every call.
const GlfwLibrary& glfw();

}  // namespace sutura::render
