#pragma once
// Replaying session text in a fresh scratch directory, for the session layer's tests: the
// session file is named `dir/s.jsonl` (relative paths in it resolve there) and the outputs go
// to `dir/out`.
#include <filesystem>
#include <string>

#include <unistd.h>

#include "sutura/app/replay.hpp"
#include "sutura/app/session.hpp"

namespace sutura::testing {

/// An empty directory `sutura_<group>_<name>_<pid>` under the system's temporary directory.
inline std::filesystem::path scratch_dir(const std::string& group, const std::string& name) {
  const std::filesystem::path d =
      std::filesystem::temp_directory_path() / ("sutura_" + group + "_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// Parses `text` as the session `dir/s.jsonl` and replays it into `dir/out`; throws as
/// app::replay does (SessionError naming the line).
inline app::ReplayResult replay_text(const std::string& text, const std::filesystem::path& dir) {
  app::ReplayOptions o;
  o.out_dir = dir / "out";
  return app::replay(app::parse_session(text, dir / "s.jsonl"), o);
}

}  // namespace sutura::testing
