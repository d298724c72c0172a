// Fuzz target: bytes become a mesh file (the first byte picks .stl, .obj or .ply) and are
// loaded. Success or a sutura::engine::Error (a LoadError naming the problem) is fine; any
// other exception, a sanitizer report or a hang is a finding. See fuzz_session.cpp.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".stl", ".obj", ".ply"};
  const fs::path file = fs::temp_directory_path() /
                        ("sutura_fuzz_mesh_" + std::to_string(::getpid()) + kExtensions[data[0] % 3]);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), std::streamsize(size - 1));
  }
  try {
    (void)sutura::engine::load_mesh(file);
  } catch (const sutura::engine::Error&) {
  }
  std::error_code ec;
  fs::remove(file, ec);
  return 0;
}
