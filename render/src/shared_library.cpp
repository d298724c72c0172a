#include "shared_library.hpp"

#include <dlfcn.h>

#include <utility>

#include "sutura/render/context.hpp"

namespace sutura::render::detail {

SharedLibrary::SharedLibrary(std::string soname, const std::string& purpose, std::string package,
                             std::string requirement)
    : soname_(std::move(soname)), package_(std::move(package)), requirement_(std::move(requirement)) {
  handle_ = dlopen(soname_.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle_ == nullptr) {
    const char* why = dlerror();
    throw GlError("cannot load " + soname_ + " " + purpose + " (install the Debian package " +
                  package_ + "): " + (why != nullptr ? why : "unknown error"));
  }
}

void* SharedLibrary::symbol(const char* name) {
  void* fn = dlsym(handle_, name);
  if (fn == nullptr) {
    dlclose(handle_);
    throw GlError(soname_ + " has no " + name + " (" + requirement_ + " is needed; Debian package " +
                  package_ + ")");
  }
  return fn;
}

}  // namespace sutura::render::detail
