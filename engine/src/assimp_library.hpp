#pragma once
// assimp, loaded at the first mesh file it reads, not when the program starts.
//
// Why: a replay that generates its anatomy, or `sutura --version`, has no use for assimp and
// the libraries it brings (draco, minizip); dlopen defers them to the first `load`, and a
// machine without them can still run everything else. assimp's C interface (cimport.h) is
// used: plain functions that dlsym can resolve. Its last-error string is global, so imports
// are serialised by `lock`.
#include <assimp/cimport.h>

#include <mutex>
#include <string>

namespace sutura::engine::detail {

struct AssimpLibrary {
  const aiScene* (*import_file)(const char* file, unsigned int flags) = nullptr;
  const aiScene* (*import_memory)(const char* buffer, unsigned int length, unsigned int flags,
                                  const char* hint) = nullptr;
  /// In place; nullptr when it failed (the scene is then already released).
  const aiScene* (*apply_post_processing)(const aiScene* scene, unsigned int flags) = nullptr;
  void (*release)(const aiScene* scene) = nullptr;
  const char* (*error_string)() = nullptr;
  std::mutex* lock = nullptr;  ///< held around an import and the reading of its error
};

/// Loads `soname` (RTLD_NOW | RTLD_LOCAL) and resolves the entry points; never unloaded.
/// Throws std::runtime_error naming the library, the Debian package (libassimp5) and dlerror().
AssimpLibrary load_assimp(const std::string& soname);

/// load_assimp("libassimp.so.5"), once per process (thread-safe); a failure is thrown again on
/// every call.
const AssimpLibrary& assimp();

}  // namespace sutura::engine::detail
