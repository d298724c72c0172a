#include "sutura/render/glfw_library.hpp"

#include <dlfcn.h>

#include <mutex>
#include <optional>
#include <type_traits>

#include "sutura/render/context.hpp"

namespace sutura::render {

GlfwLibrary load_glfw(const std::string& soname) {
  void* handle = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw GlError("cannot load " + soname + " to open a window (install the Debian package "
                  "libglfw3): " + (why != nullptr ? why : "unknown error"));
  }
  GlfwLibrary g;
  const auto resolve = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
    if (fn == nullptr) {
      dlclose(handle);
      throw GlError(soname + " has no " + name + " (GLFW 3.3 or newer is needed; Debian package "
                    "libglfw3)");
    }
  };
  resolve(g.init, "glfwInit");
  resolve(g.terminate, "glfwTerminate");
  resolve(g.get_error, "glfwGetError");
  resolve(g.default_window_hints, "glfwDefaultWindowHints");
  resolve(g.window_hint, "glfwWindowHint");
  resolve(g.create_window, "glfwCreateWindow");
  resolve(g.destroy_window, "glfwDestroyWindow");
  resolve(g.make_context_current, "glfwMakeContextCurrent");
  resolve(g.get_proc_address, "glfwGetProcAddress");
  resolve(g.swap_buffers, "glfwSwapBuffers");
  resolve(g.swap_interval, "glfwSwapInterval");
  resolve(g.poll_events, "glfwPollEvents");
  resolve(g.wait_events_timeout, "glfwWaitEventsTimeout");
  resolve(g.window_should_close, "glfwWindowShouldClose");
  resolve(g.set_window_should_close, "glfwSetWindowShouldClose");
  resolve(g.set_window_user_pointer, "glfwSetWindowUserPointer");
  resolve(g.get_window_user_pointer, "glfwGetWindowUserPointer");
  resolve(g.get_window_size, "glfwGetWindowSize");
  resolve(g.get_framebuffer_size, "glfwGetFramebufferSize");
  resolve(g.create_standard_cursor, "glfwCreateStandardCursor");
  resolve(g.destroy_cursor, "glfwDestroyCursor");
  resolve(g.set_cursor, "glfwSetCursor");
  resolve(g.set_key_callback, "glfwSetKeyCallback");
  resolve(g.set_char_callback, "glfwSetCharCallback");
  resolve(g.set_mouse_button_callback, "glfwSetMouseButtonCallback");
  resolve(g.set_cursor_pos_callback, "glfwSetCursorPosCallback");
  resolve(g.set_scroll_callback, "glfwSetScrollCallback");
  return g;
}

const GlfwLibrary& glfw() {
  static std::mutex mutex;
  static std::optional<GlfwLibrary> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!loaded) loaded = load_glfw("libglfw.so.3");
  return *loaded;
}

}  // namespace sutura::render
