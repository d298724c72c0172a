// Runs a fuzz target (LLVMFuzzerTestOneInput) once on every file given, directories
// recursively, in sorted order, so that ctest replays the fuzz corpora with the ordinary
// compiler (no libFuzzer needed). For a mesh target, `--as-mesh` prefixes each file with the
// byte that picks its extension (.stl 0, .obj 1, .ply 2), as fuzz_mesh.cpp expects. Exits 1
// (the target's exception escapes, or a sanitizer aborts) on a finding, 0 otherwise.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  bool as_mesh = false;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--as-mesh") {
      as_mesh = true;
    } else if (fs::is_directory(arg)) {
      for (const auto& e : fs::recursive_directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
    } else {
      files.emplace_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    std::ifstream in(f, std::ios::binary);
    std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (as_mesh) {
      const std::string ext = f.extension().string();
      const char pick = ext == ".stl" ? 0 : ext == ".obj" ? 1 : ext == ".ply" ? 2 : -1;
      if (pick < 0) continue;
      bytes.insert(bytes.begin(), pick);
    }
    std::printf("%s (%zu bytes)\n", f.c_str(), bytes.size());
    std::fflush(stdout);
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::printf("%zu inputs, no finding\n", files.size());
  return 0;
}
