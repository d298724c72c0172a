#pragma once
// The OpenGL 3.3 core renderer shared by headless snapshots and the GUI.
//
// Cost: constructing compiles the shaders (a few ms on llvmpipe); each draw uploads the
// scene's arrays to GL buffers, so scene arrays may change freely between calls.
#include <memory>

#include "sutura/render/camera.hpp"
#include "sutura/render/context.hpp"
#include "sutura/render/image.hpp"
#include "sutura/render/scene.hpp"

namespace sutura::render {

struct RenderOptions {
  int samples = 4;          ///< MSAA samples for anti-aliasing (1 = off)
  bool draw_legend = true;  ///< colour bar with min/max and label when the scene has one
};

class Renderer {
 public:
  /// Makes `context` current and compiles shaders; the context must outlive the renderer.
  explicit Renderer(GlContext& context);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Renders into an off-screen multisampled framebuffer and reads it back.
  /// Throws GlError on GL failure or a size outside [1, 8192].
  Image render(const Scene& scene, const Camera& camera, int width, int height,
               const RenderOptions& options = {});

  /// Draws into the currently bound framebuffer (the GUI's window) with a viewport of
  /// width x height.
  void draw(const Scene& scene, const Camera& camera, int width, int height,
            const RenderOptions& options = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sutura::render
