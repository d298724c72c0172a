#pragma once
// Where a session may write: only inside the output directory given on the command line.
// A session file may come from someone else, so absolute paths, `..` components and
// symbolic links leading out of the directory are rejected before anything is written.
#include <filesystem>
#include <string>

#include "sutura/engine/atomic_file.hpp"

namespace sutura::app {

/// Every file the session layer and the window write (outputs, recordings, screenshots) is
/// written whole or not at all: a temporary beside the target, then a rename.
using engine::write_file_atomically;

/// Returns out_dir / relative after checking that `relative` is non-empty, not absolute,
/// has no `..` component and — once its existing parents are resolved through symlinks —
/// stays inside out_dir. Creates the missing parent directories. Throws std::invalid_argument
/// with a message saying why the path is refused.
std::filesystem::path resolve_output_path(const std::filesystem::path& out_dir,
                                          const std::filesystem::path& relative);

/// Checks `relative` the same way without touching the file system (used while parsing, so a
/// bad path is reported with its line before the session runs). Returns an empty string when
/// acceptable, else the reason.
std::string output_path_problem(const std::filesystem::path& relative);

}  // namespace sutura::app
