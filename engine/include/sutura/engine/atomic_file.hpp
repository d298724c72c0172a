#pragma once
// Atomic file output: write to a temporary sibling, fsync, rename over the target.
// A crash or error mid-write leaves the previous file (or none), never a truncated one.
#include <filesystem>
#include <functional>
#include <string_view>

namespace sutura::engine {

/// Calls `write(tmp_path)` to produce the content in a temporary file next to `target`,
/// then renames it into place. If `write` throws, the temporary file is removed and the
/// exception propagates. Throws std::runtime_error naming `target` when the rename fails.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(const std::filesystem::path& tmp)>& write);

/// Writes `bytes` to `target` atomically.
void write_file_atomically(const std::filesystem::path& target, std::string_view bytes);

}  // namespace sutura::engine
