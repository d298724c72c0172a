#include "offscreen_target.hpp"

#include <string>

namespace sutura::render {
namespace {

void check_complete(const GlApi& gl, GLenum target, const char* what) {
  const GLenum status = gl.CheckFramebufferStatus(target);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError(std::string(what) + " framebuffer incomplete (status " + std::to_string(status) +
                  ")");
  }
}

}  // namespace

OffscreenTarget::~OffscreenTarget() { release(); }

void OffscreenTarget::release() {
  gl_.DeleteFramebuffers(1, &multisampled_);
  gl_.DeleteFramebuffers(1, &resolved_);
  gl_.DeleteRenderbuffers(3, renderbuffers_);
  multisampled_ = resolved_ = 0;
  renderbuffers_[0] = renderbuffers_[1] = renderbuffers_[2] = 0;
  width_ = height_ = samples_ = 0;
}

void OffscreenTarget::ensure(int width, int height, int samples) {
  if (width == width_ && height == height_ && samples == samples_) return;
  release();
  gl_.GenRenderbuffers(3, renderbuffers_);
  const GLuint ms_color = renderbuffers_[0];
  const GLuint depth = renderbuffers_[1];
  const GLuint color = renderbuffers_[2];

  gl_.BindRenderbuffer(GL_RENDERBUFFER, color);
  gl_.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, depth);
  gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples > 1 ? samples : 0,
                                     GL_DEPTH_COMPONENT24, width, height);
  gl_.GenFramebuffers(1, &resolved_);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, resolved_);
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
  if (samples > 1) {
    gl_.BindRenderbuffer(GL_RENDERBUFFER, ms_color);
    gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    gl_.GenFramebuffers(1, &multisampled_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, multisampled_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ms_color);
  }
  gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  gl_.BindRenderbuffer(GL_RENDERBUFFER, 0);
  width_ = width;
  height_ = height;
  samples_ = samples;
  try {
    gl_.check("allocating the off-screen framebuffer");
    if (samples > 1) check_complete(gl_, GL_FRAMEBUFFER, "multisampled");
    gl_.BindFramebuffer(GL_FRAMEBUFFER, resolved_);
    check_complete(gl_, GL_FRAMEBUFFER, "resolve");
  } catch (...) {
    release();
    throw;
  }
}

void OffscreenTarget::resolve() {
  if (samples_ > 1) {
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, multisampled_);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved_);
    gl_.BlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT,
                        GL_NEAREST);
  }
  gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resolved_);
}

}  // namespace sutura::render
