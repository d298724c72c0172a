// Headless OpenGL 3.3 core context through OSMesa (Mesa's gallium llvmpipe on the CPU).
#include <GL/osmesa.h>

#include <array>
#include <cstdint>

#include "sutura/render/context.hpp"

namespace sutura::render {
namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() {
    // The default framebuffer is only a 4x4 dummy: OSMesa needs one to make the context
    // current, while the renderer draws into framebuffer objects of any size. No depth or
    // stencil bits for it, so it costs nothing.
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              0,
                              OSMESA_STENCIL_BITS,
                              0,
                              OSMESA_ACCUM_BITS,
                              0,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              3,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              3,
                              0};
    context_ = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context_ == nullptr) {
      throw GlError("cannot create an OSMesa OpenGL 3.3 core context (is Mesa >= 20 installed?)");
    }
    try {
      make_current();
    } catch (...) {
      OSMesaDestroyContext(context_);
      throw;
    }
  }

  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  void make_current() override {
    if (!OSMesaMakeCurrent(context_, dummy_.data(), GL_UNSIGNED_BYTE, kDummySize, kDummySize)) {
      throw GlError("OSMesaMakeCurrent failed");
    }
  }

  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
  }

 private:
  static constexpr int kDummySize = 4;
  OSMesaContext context_ = nullptr;
  std::array<std::uint8_t, 4 * kDummySize * kDummySize> dummy_{};
};

}  // namespace

std::unique_ptr<GlContext> create_offscreen_context() { return std::make_unique<OsMesaContext>(); }

}  // namespace sutura::render
