#pragma once
// Appends the GUI's actions to a session file as they happen (JSON Lines, flushed after
// every line, so a crash loses nothing), and takes back the last line of an action that
// failed or was cancelled, so the file always replays to what the window shows.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sutura::ui {

class SessionRecorder {
 public:
  /// Creates `file` (parent directories too) with the header line {"format":
  /// "sutura-session", "version": ..., "units": "mm", "description": ...}. Never replaces a
  /// file: one that exists is an error (created exclusively, O_EXCL, so no two recorders, in
  /// this process or another, ever share a file). Throws std::runtime_error when it exists or
  /// cannot be written.
  static SessionRecorder create(const std::filesystem::path& file, const std::string& description);
  /// Continues the session `from` in the new file `file`: `file` is created as create() does
  /// (never an existing one) with `from`'s content (a missing final newline added; a load op's
  /// relative mesh path named again from `file`'s directory, so it reaches the same mesh), and
  /// later lines are appended after it; `from` is only read, never written. Throws
  /// std::runtime_error when `from` cannot be read or `file` exists or cannot be written.
  static SessionRecorder continue_in(const std::filesystem::path& from, const std::filesystem::path& file);

  SessionRecorder(SessionRecorder&& other) noexcept;
  SessionRecorder& operator=(SessionRecorder&&) = delete;
  SessionRecorder(const SessionRecorder&) = delete;
  ~SessionRecorder();

  /// Writes `op` as one line, flushed to the OS; returns its 1-based line number in the
  /// file. Throws std::runtime_error on a write error, or, writing nothing, when a string in
  /// `op` is not valid UTF-8.
  int append(const nlohmann::json& op);
  /// Removes the line written by the last append() (truncates the file to where it
  /// started). Lines appended before this recorder was opened are never removed.
  /// Throws std::logic_error when there is no such line.
  void drop_last();
  /// Copies the file as it is now to `target` (File > Save session as), atomically (a
  /// temporary file renamed over it), relative mesh paths named again from `target`'s
  /// directory; recording goes on in the original file. Throws std::runtime_error on failure
  /// or when `target` is the recording itself or the session it continues.
  void save_as(const std::filesystem::path& target) const;

  [[nodiscard]] const std::filesystem::path& file() const { return file_; }
  [[nodiscard]] int lines() const { return lines_; }  ///< lines in the file, header included
  /// The format version of the file's header: app::kSessionFormatVersion for a new recording,
  /// the continued session's own for continue_in (its new lines mean what they would mean in
  /// that version, so the file replays as the window ran it).
  [[nodiscard]] int format_version() const { return version_; }

 private:
  SessionRecorder(std::filesystem::path file, std::FILE* out, int lines);

  std::filesystem::path file_;
  std::filesystem::path opened_;  ///< the session continued here (continue_in); empty: none
  std::FILE* out_ = nullptr;
  int lines_ = 0;
  int version_ = 0;
  std::vector<long> line_starts_;  ///< byte offsets of the lines appended by this recorder
};

}  // namespace sutura::ui
