#include "sutura/ui/session_recorder.hpp"

#include "sutura/app/session.hpp"

#include <fstream>
#include <stdexcept>
#include <string>

namespace sutura::ui {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
  throw std::runtime_error("session file " + file.string() + ": " + what);
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
  std::FILE* out = std::fopen(file.c_str(), "wb");
  if (out == nullptr) fail(file, "cannot be created");
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
  if (last != '\n') {
    std::fputc('\n', out);
    ++lines;
  }
  std::fflush(out);
  return SessionRecorder(file, out, lines);
}

int SessionRecorder::append(const nlohmann::json& op) {
  const std::string line = op.dump() + "\n";
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
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  fs::copy_file(file_, target, fs::copy_options::overwrite_existing, ec);
  if (ec) throw std::runtime_error("cannot save the session as " + target.string() + ": " + ec.message());
}

}  // namespace sutura::ui
