// GLFW window with an OpenGL 3.3 core forward-compatible context.
//
// GLFW must be used from the main thread only; that holds for WindowContext too. GLFW is
// initialised by the first live window and terminated with the last one.
#include <cstdlib>
#include <string>

#include "sutura/render/context.hpp"
#include "sutura/render/glfw_library.hpp"

namespace sutura::render {
namespace {

int g_live_windows = 0;  // main thread only, like GLFW itself

std::string last_glfw_error() {
  const char* description = nullptr;
  render::glfw().get_error(&description);
  return description != nullptr ? description : "unknown GLFW error";
}

bool display_variable_set() {
  const char* x11 = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x11 != nullptr && *x11 != '\0') || (wayland != nullptr && *wayland != '\0');
}

GLFWwindow* as_glfw(void* window) { return static_cast<GLFWwindow*>(window); }

}  // namespace

WindowContext::WindowContext(int width, int height, const std::string& title,
                             bool visible, int samples) {
  if (width < 1 || height < 1) {
    throw GlError("cannot open a window of " + std::to_string(width) + "x" +
                  std::to_string(height) + " pixels");
  }
  if (g_live_windows == 0 && render::glfw().init() != GLFW_TRUE) {
    std::string message = "cannot open a window: " + last_glfw_error();
    if (!display_variable_set()) message += " (no display: is DISPLAY set? run under Xvfb)";
    throw GlError(message);
  }
  ++g_live_windows;

  render::glfw().default_window_hints();  // hints are global; start from a known state
  render::glfw().window_hint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  render::glfw().window_hint(GLFW_CONTEXT_VERSION_MINOR, 3);
  render::glfw().window_hint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  render::glfw().window_hint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  render::glfw().window_hint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  // Anti-aliasing for Renderer::draw, which draws straight into the window. A soft
  // constraint: without multisample visuals GLFW picks a single-sampled framebuffer.
  render::glfw().window_hint(GLFW_SAMPLES, samples);

  window_ = render::glfw().create_window(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string message =
        "cannot create a window with an OpenGL 3.3 core context: " + last_glfw_error();
    if (--g_live_windows == 0) render::glfw().terminate();
    throw GlError(message);
  }
  make_current();
}

WindowContext::~WindowContext() {
  render::glfw().destroy_window(as_glfw(window_));
  if (--g_live_windows == 0) render::glfw().terminate();
}

void WindowContext::make_current() {
  // libOSMesa and Mesa's GLX driver share one current-context slot (libglapi), but GLVND
  // skips glXMakeCurrent when it believes this context is already current. After an
  // OSMesaMakeCurrent on this thread that belief is stale, so release first to force a real
  // rebind. Costs two glXMakeCurrent calls (a flush), negligible per frame.
  render::glfw().make_context_current(nullptr);
  render::glfw().make_context_current(as_glfw(window_));
}

void* WindowContext::proc_address(const char* name) const {
  return reinterpret_cast<void*>(render::glfw().get_proc_address(name));
}

}  // namespace sutura::render
