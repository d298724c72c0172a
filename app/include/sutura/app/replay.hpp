#pragma once
// Headless replay of a session: runs every action in order, writes PNGs, meshes and
// report.json inside the output directory, and reports progress.
#include <filesystem>
#include <iosfwd>

#include <nlohmann/json.hpp>

#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"

namespace sutura::app {

struct ReplayOptions {
  std::filesystem::path out_dir = "out";  ///< every output goes inside; created if missing
  std::ostream* progress = nullptr;       ///< one line per action; nullptr = silent
};

struct ReplayResult {
  Workspace workspace;   ///< final state of every object
  nlohmann::json report; ///< the content written to out_dir/report.json
};

/// Runs `session`. On success writes out_dir/report.json with status "ok". On failure writes
/// out_dir/report.json with status "failed" and the error (what was done up to then is kept),
/// then throws SessionError naming the line and op that failed.
ReplayResult replay(const Session& session, const ReplayOptions& options);

}  // namespace sutura::app
