// Headless OpenGL 3.3 core context through OSMesa (Mesa's gallium llvmpipe on the CPU).
#include <array>
#include <cstdint>
#include <string>

#include "osmesa_library.hpp"
#include "shared_library.hpp"
#include "sutura/render/context.hpp"

namespace sutura::render {

namespace detail {

OsMesaLibrary load_osmesa(const std::string& soname) {
  SharedLibrary library(soname, "for off-screen drawing", "libosmesa6", "Mesa 20 or newer");
  OsMesaLibrary lib;
  library.resolve(lib.create_context_attribs, "OSMesaCreateContextAttribs");
  library.resolve(lib.destroy_context, "OSMesaDestroyContext");
  library.resolve(lib.make_current, "OSMesaMakeCurrent");
  library.resolve(lib.get_proc_address, "OSMesaGetProcAddress");
  return lib;
}

const OsMesaLibrary& osmesa() {
  return load_once<OsMesaLibrary>([] { return load_osmesa("libOSMesa.so.8"); });
}

}  // namespace detail

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
    context_ = osmesa_.create_context_attribs(attributes, nullptr);
    if (context_ == nullptr) {
      throw GlError("cannot create an OSMesa OpenGL 3.3 core context (is Mesa >= 20 installed?)");
    }
    try {
      make_current();
    } catch (...) {
      osmesa_.destroy_context(context_);
      throw;
    }
  }

  ~OsMesaContext() override { osmesa_.destroy_context(context_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  void make_current() override {
    if (!osmesa_.make_current(context_, dummy_.data(), GL_UNSIGNED_BYTE, kDummySize, kDummySize)) {
      throw GlError("OSMesaMakeCurrent failed");
    }
  }

  void* proc_address(const char* name) const override {
    return reinterpret_cast<void*>(osmesa_.get_proc_address(name));
  }

 private:
  static constexpr int kDummySize = 4;
  const detail::OsMesaLibrary& osmesa_ = detail::osmesa();  // first: throws when it cannot load
  OSMesaContext context_ = nullptr;
  std::array<std::uint8_t, 4 * kDummySize * kDummySize> dummy_{};
};

}  // namespace

std::unique_ptr<GlContext> create_offscreen_context() { return std::make_unique<OsMesaContext>(); }

}  // namespace sutura::render
