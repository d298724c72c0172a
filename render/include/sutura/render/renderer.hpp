#pragma once
// The OpenGL 3.3 core renderer shared by headless snapshots and the GUI.
//
// Cost: constructing compiles the shaders (a few ms on llvmpipe); llvmpipe JIT-compiles
// them at the first render of a process (~0.1-0.4 s, less when Mesa's on-disk shader cache,
// ~/.cache/mesa_shader_cache, already holds them). Each draw uploads the scene's arrays to
// GL buffers (reusing their storage), so scene arrays may change freely between calls.
// A Renderer and its context are used by one thread at a time.
#include <memory>

#include "sutura/render/camera.hpp"
#include "sutura/render/context.hpp"
#include "sutura/render/image.hpp"
#include "sutura/render/scene.hpp"

namespace sutura::render {

struct RenderOptions {
  int samples = 4;          ///< MSAA samples for anti-aliasing (1 = off)
  bool draw_legend = true;  ///< colour bar with min/max and label when the scene has one
  /// Keep the legend's column free without drawing the legend (the left view of a pair whose
  /// right view has it, so that both frame the scene alike).
  bool legend_space = false;
  /// draw() only: lower-left corner, in pixels of the bound framebuffer, of the area drawn
  /// (and cleared); render() ignores it.
  int viewport_x = 0;
  int viewport_y = 0;
};

/// Pixels of the column the scene's legend takes at the right edge of a width x height view:
/// 0 without a colour map, with its show_legend off, or when the legend would not fit (more
/// than half the width, even in the smallest font: a narrow view gets a smaller font). With a
/// legend drawn (or legend_space), the scene is drawn in the view less this column, with that
/// part's aspect, so that the legend never covers it: fit cameras and cast picking rays for
/// (width - legend_width) x height.
int legend_width(const Scene& scene, int width, int height);

/// The MSAA samples render() uses: `requested`, clamped to [1, max_samples] (GL_MAX_SAMPLES;
/// 4 on llvmpipe) and to at most 4 x 4096 x 4096 samples in all, so 4 up to 4096 x 4096
/// pixels, 2 up to 5792 x 5792 and 1 at 8192 x 8192 (each sample costs 8 bytes of memory that
/// is cleared per render).
int render_samples(int requested, int width, int height, int max_samples);

class Renderer {
 public:
  /// Makes `context` current and compiles shaders; the context must outlive the renderer.
  explicit Renderer(GlContext& context);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Makes the context current, renders into an off-screen framebuffer with
  /// render_samples(options.samples, ...) samples, resolves it
  /// and reads it back (top row first, alpha 255). The framebuffer bindings found on entry
  /// are restored. Same scene, camera, size and options give the same bytes on one build.
  /// Throws GlError on GL failure or a size outside [1, 8192] (the message names the size),
  /// std::invalid_argument for inconsistent surface arrays (see SurfaceItem) or a camera
  /// that view_matrix/projection_matrix reject.
  Image render(const Scene& scene, const Camera& camera, int width, int height,
               const RenderOptions& options = {});

  /// Draws into the currently bound framebuffer (the GUI's window) with a viewport of
  /// width x height at (options.viewport_x, options.viewport_y), clearing only that area
  /// first (scissor test, off again on return). The context must be current. Anti-aliasing is that
  /// of the bound framebuffer (WindowContext asks for 4 samples); options.samples is
  /// ignored. Leaves depth test off and program, vertex array, buffer and texture bindings
  /// at 0. Throws like render().
  void draw(const Scene& scene, const Camera& camera, int width, int height,
            const RenderOptions& options = {});

  /// The lower-left width x height pixels of the bound read framebuffer (the GUI window's
  /// back buffer after drawing a frame), top row first, alpha 255. The context must be
  /// current. Throws GlError like render().
  Image read_framebuffer(int width, int height);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sutura::render
