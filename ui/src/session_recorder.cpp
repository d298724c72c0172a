#include "sutura/ui/session_recorder.hpp"

#include "sutura/app/session.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>

#include "sutura/app/op_builders.hpp"
#include "sutura/app/output_paths.hpp"

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
      opened_(std::move(other.opened_)),
      out_(other.out_),
      lines_(other.lines_),
      version_(other.version_),
      line_starts_(std::move(other.line_starts_)) {
  other.out_ = nullptr;
}

SessionRecorder::~SessionRecorder() {
  if (out_ != nullptr) std::fclose(out_);
}

namespace {

// `content` (a session's lines, read from `from`) as the file `to` must hold them: a load op's
// relative mesh path is read from its session's own directory, so it is named again as seen
// from `to` (path_from: relative inside `to`'s directory, else absolute); every other line is
// kept byte for byte.
std::string rebased(const std::string& content, const fs::path& from, const fs::path& to) {
  const fs::path from_dir = fs::absolute(from).parent_path().lexically_normal();
  if (from_dir == fs::absolute(to).parent_path().lexically_normal()) return content;
  std::string out;
  out.reserve(content.size());
  for (std::size_t start = 0; start < content.size();) {
    const std::size_t end = content.find('\n', start);
    const std::size_t stop = end == std::string::npos ? content.size() : end + 1;
    std::string line = content.substr(start, stop - start);
    start = stop;
    if (line.find("\"load\"") != std::string::npos) {
      try {
        nlohmann::json j = nlohmann::json::parse(line);
        if (j.is_object() && j.value("op", "") == "load" && j.contains("file") && j["file"].is_string() &&
            fs::path(j["file"].get<std::string>()).is_relative()) {
          j["file"] = app::path_from(from_dir / j["file"].get<std::string>(), to).string();
          line = j.dump() + (end == std::string::npos ? "" : "\n");
        }
      } catch (const nlohmann::json::exception&) {
        // Not a line this can read: kept as it is (the replay names its error).
      }
    }
    out += line;
  }
  return out;
}

// `file` created exclusively (parent directories too): an existing file (an earlier
// recording, an input, another window's recording) is never replaced nor shared.
std::FILE* create_exclusively(const fs::path& file) {
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST)
      fail(file, "exists already, and a recording is never overwritten: open it to continue it "
                 "in a new file (sutura gui " + file.string() + "), or record into a new file");
    fail(file, "cannot be created");
  }
  std::FILE* out = ::fdopen(fd, "wb");
  if (out == nullptr) {
    ::close(fd);
    fail(file, "cannot be created");
  }
  return out;
}

}  // namespace

SessionRecorder SessionRecorder::create(const fs::path& file, const std::string& description) {
  SessionRecorder r(file, create_exclusively(file), 0);
  r.version_ = app::kSessionFormatVersion;
  const nlohmann::json header = {{"format", "sutura-session"},
                                 {"version", app::kSessionFormatVersion},
                                 {"units", "mm"},
                                 {"description", description}};
  r.append(header);
  r.line_starts_.clear();  // the header is never taken back
  return r;
}

SessionRecorder SessionRecorder::continue_in(const fs::path& from, const fs::path& file) {
  std::ifstream in(from, std::ios::binary);
  if (!in) fail(from, "cannot be opened for reading");
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) fail(from, "cannot be read");
  if (!content.empty() && content.back() != '\n') content += '\n';
  content = rebased(content, from, file);
  // The header's version (the first line that is not blank, as the session parser reads it).
  int version = 0;
  {
    std::istringstream text(content);
    std::string first;
    while (std::getline(text, first) && first.find_first_not_of(" \t\r") == std::string::npos) {
    }
    const nlohmann::json header = nlohmann::json::parse(first, nullptr, false);
    if (header.is_object() && header.contains("version") && header["version"].is_number_integer())
      version = header["version"].get<int>();
    if (version < 1 || version > app::kSessionFormatVersion)
      fail(from, "has no session header this build reads (format version 1 to " +
                     std::to_string(app::kSessionFormatVersion) + ")");
  }
  const auto lines = static_cast<int>(std::count(content.begin(), content.end(), '\n'));
  std::FILE* out = create_exclusively(file);
  SessionRecorder r(file, out, lines);  // closes `out` should the copy fail
  r.opened_ = from;
  r.version_ = version;
  if (std::fwrite(content.data(), 1, content.size(), out) != content.size() || std::fflush(out) != 0) {
    std::error_code ignored;
    fs::remove(file, ignored);  // our own new file, half written
    fail(file, "cannot be written");
  }
  return r;
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
  if (!opened_.empty() && fs::equivalent(opened_, target, ec))
    throw std::runtime_error("cannot save the session as " + target.string() +
                             ": it is the session opened, which is never written");
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  std::ifstream in(file_, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw std::runtime_error("cannot save the session as " + target.string() + ": the recording cannot be read");
  try {
    // A reader never sees half a file.
    app::write_file_atomically(target, rebased(text.str(), file_, target));
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot save the session as " + target.string() + ": " + e.what());
  }
}

}  // namespace sutura::ui
