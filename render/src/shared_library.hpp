#pragma once
// A library the renderer opens on first use (OSMesa, GLFW), not at the program's start: dlopen
// with RTLD_NOW | RTLD_LOCAL and its entry points resolved into a table of function pointers.
// Every error names the library and the Debian package that provides it. A library is closed
// again only when an entry point is missing; once resolved it stays loaded (a GL or window
// library is not safe to unload).
#include <mutex>
#include <optional>
#include <string>

namespace sutura::render::detail {

class SharedLibrary {
 public:
  /// Opens `soname`. Throws GlError "cannot load <soname> <purpose> (install the Debian package
  /// <package>): <dlerror>". `requirement` (e.g. "Mesa 20 or newer") is what a library without
  /// an entry point lacks.
  SharedLibrary(std::string soname, const std::string& purpose, std::string package,
                std::string requirement);

  /// fn = the entry point `name`. When there is none, closes the library and throws GlError
  /// "<soname> has no <name> (<requirement> is needed; Debian package <package>)".
  template <class Fn>
  void resolve(Fn& fn, const char* name) {
    fn = reinterpret_cast<Fn>(symbol(name));
  }

 private:
  void* symbol(const char* name);

  void* handle_ = nullptr;
  std::string soname_, package_, requirement_;
};

/// The table `load()` makes, made once per process (thread-safe). A load that throws is tried
/// again at the next call, so every user of a missing library reports it. One table per
/// (Table, Load) pair: call it from one function per library.
template <class Table, class Load>
const Table& load_once(Load load) {
  static std::mutex mutex;
  static std::optional<Table> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  if (!loaded) loaded = load();
  return *loaded;
}

}  // namespace sutura::render::detail
