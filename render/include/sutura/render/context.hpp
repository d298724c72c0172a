#pragma once
// OpenGL 3.3 core contexts behind one interface: OSMesa off-screen (headless snapshots,
// CI, `sutura replay`) and a GLFW window (the GUI). The renderer loads every GL entry point
// through `proc_address`, so the process never links libGL directly and OSMesa's and the
// window system's GL can coexist in one executable.
#include <memory>
#include <stdexcept>
#include <string>

namespace sutura::render {

class GlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void make_current() = 0;
  /// Address of a GL function for this context, or nullptr. The context must be current
  /// (GLFW requires it; the renderer calls make_current() before loading).
  virtual void* proc_address(const char* name) const = 0;
};

/// Headless context (OSMesa, llvmpipe on CPU). The default framebuffer is a small dummy;
/// all rendering goes to framebuffer objects. libOSMesa is loaded by the first call. Throws
/// GlError if it cannot be loaded (the message names the Debian package) or a 3.3 core context
/// cannot be created.
std::unique_ptr<GlContext> create_offscreen_context();

/// A GLFW window with a 3.3 core context. `visible = false` creates a hidden window.
/// `samples`: multisampling of the window's framebuffer for anti-aliasing (a request; 0 =
/// off, much faster on llvmpipe).
/// Throws GlError when no display is available or context creation fails.
/// GLFW rules apply: create, use and destroy windows on the main thread only.
/// Mixing with an off-screen context on one thread: OSMesa and Mesa's GLX share one
/// "current context" slot that GLFW does not see, so after any off-screen rendering call
/// make_current() (not glfwMakeContextCurrent) before further GL calls or glfwSwapBuffers
/// on the window.
class WindowContext : public GlContext {
 public:
  WindowContext(int width, int height, const std::string& title, bool visible = true,
                int samples = 4);
  ~WindowContext() override;
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;
  void make_current() override;
  void* proc_address(const char* name) const override;
  /// The underlying GLFWwindow* (for the GUI's input callbacks), as void* to keep GLFW out
  /// of this header.
  [[nodiscard]] void* native_window() const { return window_; }

 private:
  void* window_ = nullptr;
};

}  // namespace sutura::render
