#include "sutura/ui/session_recorder.hpp"

#include "sutura/app/session.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sutura/engine/atomic_file.hpp"

namespace sutura::ui {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  throw std::runtime_error("session file " + file.string() + ": " + what);
}

// Takes the recording's exclusive advisory lock for as long as `out` is open: a second GUI
// recording into the same file would interleave its lines with this one's.
void lock_or_fail(std::FILE* out, const fs::path& file) {
  if (::flock(::fileno(out), LOCK_EX | LOCK_NB) != 0) {
    std::fclose(out);
    fail(file, "is being recorded by another sutura gui; open a copy, or wait until that window is closed");
  }
}

}  // namespace

SessionRecorder::SessionRecorder(fs::path file, std::FILE* out, int lines)
    : file_(std::move(file)), out_(out), lines_(lines) {}

SessionRecorder::SessionRecorder(SessionRecorder&& other) noexcept
    : file_(std::move(other.file_)),
      out_(other.out_),
      lines_(other.lines_),
      line_starts_(std::move(other.line_starts_)) {
  other.out_ = nullptr;
}

SessionRecorder::~SessionRecorder() {
  if (out_ != nullptr) std::fclose(out_);
}

SessionRecorder SessionRecorder::create(const fs::path& file, const std::string& description) {
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
  // Exclusive creation: an existing file (an earlier recording, an input) is never replaced.
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST)
      fail(file, "exists already, and a recording is never overwritten: open it to continue it "
                 "(sutura gui " + file.string() + "), or record into a new file");
    fail(file, "cannot be created");
  }
  std::FILE* out = ::fdopen(fd, "wb");
  if (out == nullptr) {
    ::close(fd);
    fail(file, "cannot be created");
  }
  lock_or_fail(out, file);
  SessionRecorder r(file, out, 0);
  const nlohmann::json header = {{"format", "sutura-session"},
                                 {"version", app::kSessionFormatVersion},
                                 {"units", "mm"},
                                 {"description", description}};
  r.append(header);
  r.line_starts_.clear();  // the header is never taken back
  return r;
}

SessionRecorder SessionRecorder::resume(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot be opened for reading");
  int lines = 0;
  char last = '\n';
  for (char c; in.get(c);) {
    if (c == '\n') ++lines;
    last = c;
  }
  std::FILE* out = std::fopen(file.c_str(), "ab");
  if (out == nullptr) fail(file, "cannot be opened for appending");
  lock_or_fail(out, file);
  if (last != '\n') {
    std::fputc('\n', out);
    ++lines;
  }
  std::fflush(out);
  return SessionRecorder(file, out, lines);
}

int SessionRecorder::append(const nlohmann::json& op) {
  std::string line;
  try {
    line = op.dump() + "\n";
  } catch (const nlohmann::json::type_error&) {
    // Text that is not UTF-8 (a file name typed in another encoding) cannot be a JSON line;
    // recorded as U+FFFD it would replay as another name. The op is refused before it runs.
    throw std::runtime_error("cannot record this action: a name in it is not valid UTF-8");
  }
  std::fseek(out_, 0, SEEK_END);
  const long start = std::ftell(out_);
  if (std::fwrite(line.data(), 1, line.size(), out_) != line.size() || std::fflush(out_) != 0)
    fail(file_, "write failed");
  line_starts_.push_back(start);
  return ++lines_;
}

void SessionRecorder::drop_last() {
  if (line_starts_.empty()) throw std::logic_error("SessionRecorder::drop_last: nothing to drop");
  std::fflush(out_);
  std::error_code ec;
  fs::resize_file(file_, static_cast<std::uintmax_t>(line_starts_.back()), ec);
  if (ec) fail(file_, "cannot take back the last line: " + ec.message());
  line_starts_.pop_back();
  --lines_;
}

void SessionRecorder::save_as(const fs::path& target) const {
  std::fflush(out_);
  std::error_code ec;
  if (fs::equivalent(file_, target, ec))
    throw std::runtime_error("cannot save the session as " + target.string() + ": it is the recording itself");
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  std::ifstream in(file_, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw std::runtime_error("cannot save the session as " + target.string() + ": the recording cannot be read");
  try {
    engine::write_file_atomically(target, text.str());  // a reader never sees half a file
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot save the session as " + target.string() + ": " + e.what());
  }
}

}  // namespace sutura::ui
