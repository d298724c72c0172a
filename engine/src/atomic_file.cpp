#include "sutura/engine/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <stdexcept>
#include <string>
#include <system_error>

namespace sutura::engine {

namespace fs = std::filesystem;

namespace {

std::string reason(int error) { return std::generic_category().message(error); }

fs::path directory_of(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

// Creates a new, empty, uniquely named file next to `target`. O_EXCL guarantees that two
// concurrent saves (threads or processes) never share a temporary; mode 0666 lets the umask
// decide the final permissions, as for any newly created file.
fs::path create_temporary(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = directory_of(target);
  for (int attempt = 0; attempt < 100; ++attempt) {
    // Hidden sibling: .<name>.<pid>.<n>.tmp (appended piecewise: GCC 12 gives a false
    // -Wrestrict warning for "." + std::string).
    std::string name(1, '.');
    name += target.filename().string();
    name += '.';
    name += std::to_string(::getpid());
    name += '.';
    name += std::to_string(counter++);
    name += ".tmp";
    const fs::path tmp = dir / name;
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return tmp;
    }
    if (errno != EEXIST) {
      throw std::runtime_error("cannot write " + target.string() + ": cannot create a file in " +
                               dir.string() + ": " + reason(errno));
    }
  }
  throw std::runtime_error("cannot write " + target.string() + ": no free temporary file name in " +
                           dir.string());
}

// Flushes the file's data to the disk, so that the rename never publishes a file whose content
// is still only in the page cache (after a power loss it could appear empty).
void sync_file(const fs::path& file, const fs::path& target) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || ::fsync(fd) != 0) {
    const int error = errno;
    if (fd >= 0) ::close(fd);
    throw std::runtime_error("cannot write " + target.string() +
                             ": flushing to disk failed: " + reason(error));
  }
  ::close(fd);
}

// Makes the rename itself durable. Best effort: the new file is already in place and complete,
// so a failure here is not worth reporting as a failed write.
void sync_directory(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void write_atomically(const fs::path& target,
                      const std::function<void(const fs::path& tmp)>& write) {
  if (!target.has_filename()) {
    throw std::runtime_error("cannot write " + target.string() + ": not a file name");
  }
  const fs::path tmp = create_temporary(target);
  try {
    write(tmp);
    sync_file(tmp, target);
    std::error_code error;
    fs::rename(tmp, target, error);
    if (error) {
      throw std::runtime_error("cannot write " + target.string() +
                               ": replacing it failed: " + error.message());
    }
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
  sync_directory(directory_of(target));
}

void write_file_atomically(const fs::path& target, std::string_view bytes) {
  write_atomically(target, [&](const fs::path& tmp) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) {
      throw std::runtime_error("cannot write " + target.string() + ": " + reason(errno));
    }
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        const int error = errno;
        ::close(fd);
        throw std::runtime_error("cannot write " + target.string() + ": " + reason(error));
      }
      done += static_cast<std::size_t>(n);
    }
    if (::close(fd) != 0) {
      throw std::runtime_error("cannot write " + target.string() + ": " + reason(errno));
    }
  });
}

}  // namespace sutura::engine
