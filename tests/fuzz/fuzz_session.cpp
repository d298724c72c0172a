// Fuzz target: a session text is parsed, checked against the limits and, when it parses, run
// with tight limits and a time limit. Any outcome but success or a SessionError (which names
// file, line and field) is a finding: another exception type escapes, a sanitizer fires, or
// it hangs past libFuzzer's -timeout. Built with libFuzzer by scripts/fuzz.sh; the corpus
// replay (corpus_main.cpp) runs the same function over tests/robustness and the bundled
// sessions in every ctest.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "sutura/app/replay.hpp"
#include "sutura/app/session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  using namespace sutura::app;
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Inputs (a `load`) resolve against the session's directory: the assets, so that the
  // bundled meshes load and nothing outside the tree is read on purpose.
  const fs::path session_file = fs::path(SUTURA_ASSETS_DIR) / "sessions" / "fuzz.jsonl";
  Session session;
  try {
    session = parse_session(text, session_file);
  } catch (const SessionError&) {
    return 0;
  }
  ReplayOptions options;
  options.out_dir = fs::temp_directory_path() / ("sutura_fuzz_" + std::to_string(::getpid()));
  options.limits.faces_per_object = 20'000;
  options.limits.faces_in_all = 40'000;
  options.limits.objects = 8;
  options.limits.steps = 200;
  options.limits.undo_megabytes = 64;
  options.limits.pixels = 256 * 256;
  options.time_limit = 2.0;
  options.threads = 1;
  try {
    replay(session, options);
  } catch (const SessionError&) {
  }
  std::error_code ec;
  fs::remove_all(options.out_dir, ec);
  return 0;
}
