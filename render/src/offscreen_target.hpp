#pragma once
// Off-screen render target: colour (RGBA8) and depth (24-bit) renderbuffers, multisampled
// when samples > 1, plus a single-sample colour buffer the multisampled one resolves into.
// Storage is reallocated only when the size or sample count changes (at 1920x1080 with 4
// samples it holds about 75 MB).
#include "gl_api.hpp"

namespace sutura::render {

class OffscreenTarget {
 public:
  explicit OffscreenTarget(const GlApi& gl) : gl_(gl) {}
  /// The context must be current.
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  /// Makes the target `width` x `height` with `samples` (>= 1) samples per pixel. Throws
  /// GlError if the framebuffer is incomplete (e.g. out of memory).
  void ensure(int width, int height, int samples);
  /// Framebuffer to draw the scene into.
  [[nodiscard]] GLuint draw_framebuffer() const { return samples_ > 1 ? multisampled_ : resolved_; }
  /// Resolves the multisampled colour (box filter over the samples, glBlitFramebuffer) and
  /// leaves the single-sample framebuffer bound for reading.
  void resolve();

 private:
  void release();

  const GlApi& gl_;
  int width_ = 0;
  int height_ = 0;
  int samples_ = 0;
  GLuint multisampled_ = 0;       // framebuffer with multisampled colour and depth
  GLuint resolved_ = 0;           // single-sample framebuffer (with depth when samples_ == 1)
  GLuint renderbuffers_[3] = {};  // multisampled colour, depth, single-sample colour
};

}  // namespace sutura::render
