#include "assimp_library.hpp"

#include <dlfcn.h>

#include <optional>
#include <stdexcept>
#include <type_traits>

namespace sutura::engine::detail {

AssimpLibrary load_assimp(const std::string& soname) {
  void* handle = dlopen(soname.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw std::runtime_error("cannot load " + soname + " to read mesh files (install the Debian "
                             "package libassimp5): " + (why != nullptr ? why : "unknown error"));
  }
  AssimpLibrary lib;
  const auto resolve = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(dlsym(handle, name));
    if (fn == nullptr) {
      dlclose(handle);
      throw std::runtime_error(soname + " has no " + name + " (Debian package libassimp5)");
    }
  };
  resolve(lib.import_file, "aiImportFile");
  resolve(lib.import_memory, "aiImportFileFromMemory");
  resolve(lib.apply_post_processing, "aiApplyPostProcessing");
  resolve(lib.release, "aiReleaseImport");
  resolve(lib.error_string, "aiGetErrorString");
  static std::mutex imports;
  lib.lock = &imports;
  return lib;
}

const AssimpLibrary& assimp() {
  static std::mutex mutex;
  static std::optional<AssimpLibrary> loaded;
  const std::lock_guard<std::mutex> guard(mutex);
  if (!loaded) loaded = load_assimp("libassimp.so.5");
  return *loaded;
}

}  // namespace sutura::engine::detail
