#pragma once
// OSMesa, loaded when the first off-screen context is made, not when the program starts.
//
// Why: libOSMesa pulls in LLVM (llvmpipe), whose relocations dominate a start of the program
// (docs/performance.md, Start-up), and a replay without snapshots never draws. dlopen defers it
// to the first snapshot; a machine without the library can still replay, and a snapshot there
// fails with a message that names the package. The symbols are resolved once, process-wide.
#include <GL/osmesa.h>

#include <string>

namespace sutura::render::detail {

/// The OSMesa entry points the off-screen context uses.
struct OsMesaLibrary {
  OSMesaContext (*create_context_attribs)(const int* attributes, OSMesaContext share) = nullptr;
  void (*destroy_context)(OSMesaContext context) = nullptr;
  GLboolean (*make_current)(OSMesaContext context, void* buffer, GLenum type, GLsizei width,
                            GLsizei height) = nullptr;
  OSMESAproc (*get_proc_address)(const char* name) = nullptr;
};

/// Loads `soname` (RTLD_NOW | RTLD_LOCAL) and resolves the entry points. Throws GlError naming
/// the library, the Debian package (libosmesa6) and dlerror() when it cannot. The library is
/// never unloaded (a GL library is not safe to unload).
OsMesaLibrary load_osmesa(const std::string& soname);

/// load_osmesa("libOSMesa.so.8"), once per process (thread-safe); a failure is thrown again on
/// every call, so a later snapshot reports it too.
const OsMesaLibrary& osmesa();

}  // namespace sutura::render::detail
