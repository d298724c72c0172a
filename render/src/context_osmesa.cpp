// Headless OpenGL 3.3 core context through OSMesa (Mesa's gallium llvmpipe on the CPU).
#include <dlfcn.h>

#include <array>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>

#include "osmesa_library.hpp"
#include "sutura/render/context.hpp"

namespace sutura::render {

namespace detail {

OsMesaLibrary load_osmesa(const std::string& soname) {
  void* handle = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw GlError("cannot load " + soname + " for off-screen drawing (install the Debian package "
                  "libosmesa6): " + (why != nullptr ? why : "unknown error"));
  }
  OsMesaLibrary lib;
  const auto resolve = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
    if (fn == nullptr) {
      dlclose(handle);
      throw GlError(soname + " has no " + name + " (Mesa 20 or newer is needed; Debian package "
                    "libosmesa6)");
    }
  };
  resolve(lib.create_context_attribs, "OSMesaCreateContextAttribs");
  resolve(lib.destroy_context, "OSMesaDestroyContext");
  resolve(lib.make_current, "OSMesaMakeCurrent");
  resolve(lib.get_proc_address, "OSMesaGetProcAddress");
  return lib;
}

const OsMesaLibrary& osmesa() {
  static std::mutex mutex;
  static std::optional<OsMesaLibrary> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!loaded) loaded = load_osmesa("libOSMesa.so.8");
  return *loaded;
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
