#include "gl_api.hpp"

#include <cstdio>
#include <string>

namespace sutura::render {

GlApi::GlApi(const GlContext& context) {
#define SUTURA_GL_LOAD(type, name)                                 \
  name = reinterpret_cast<type>(context.proc_address("gl" #name)); \
  if (name == nullptr) throw GlError("OpenGL entry point gl" #name " is not available");
  SUTURA_GL_FUNCTIONS(SUTURA_GL_LOAD)
#undef SUTURA_GL_LOAD

  GLint major = 0;
  GLint minor = 0;
  GetIntegerv(GL_MAJOR_VERSION, &major);
  GetIntegerv(GL_MINOR_VERSION, &minor);
  if (major < 3 || (major == 3 && minor < 3)) {
    const auto* version = reinterpret_cast<const char*>(GetString(GL_VERSION));
    throw GlError(std::string("OpenGL 3.3 core is required, the context reports ") +
                  (version != nullptr ? version : "no version"));
  }
  check("loading OpenGL");
}

void GlApi::check(const char* what) const {
  const GLenum first = GetError();
  if (first == GL_NO_ERROR) return;
  // Drain the queue (bounded: a lost context may report errors forever).
  for (int i = 0; i < 16 && GetError() != GL_NO_ERROR; ++i) {
  }
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(first));
  throw GlError(std::string(what) + ": GL error " + code);
}

}  // namespace sutura::render
