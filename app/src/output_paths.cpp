#include "sutura/app/output_paths.hpp"

#include <stdexcept>

namespace sutura::app {

namespace fs = std::filesystem;

std::string output_path_problem(const fs::path& relative) {
  if (relative.empty()) return "the path is empty";
  // A NUL would cut the name short where the file is opened ("evil.sh\0.obj" wrote evil.sh);
  // a newline or another control character makes a name no one can type or list safely.
  for (const char c : relative.native()) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      static const char* hex = "0123456789abcdef";
      return std::string("control characters are not allowed in names (byte 0x") + hex[byte >> 4] + hex[byte & 15] +
             (byte == 0 ? ", NUL" : byte == '\n' ? ", newline" : "") + ")";
    }
  }
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory())
    return "absolute paths are not allowed: outputs are written only inside the output directory";
  for (const auto& part : relative) {
    if (part == "..") return "'..' is not allowed: outputs are written only inside the output directory";
  }
  if (!relative.has_filename() || relative.filename() == ".")
    return "the path must name a file";
  return {};
}

namespace {
// Follows symlinks by hand: weakly_canonical() leaves a dangling link's name in place, which
// would let a link to a not-yet-existing file outside the directory pass the check.
fs::path resolve_links(fs::path p) {
  for (int hops = 0; hops < 40 && fs::is_symlink(fs::symlink_status(p)); ++hops) {
    fs::path target = fs::read_symlink(p);
    p = target.is_absolute() ? target : p.parent_path() / target;
  }
  return fs::weakly_canonical(p);
}

bool inside(const fs::path& root, const fs::path& p) {
  const fs::path rel = p.lexically_relative(root);
  return !rel.empty() && *rel.begin() != "..";
}
}  // namespace

fs::path resolve_output_path(const fs::path& out_dir, const fs::path& relative) {
  if (std::string why = output_path_problem(relative); !why.empty())
    throw std::invalid_argument("'" + relative.string() + "': " + why);
  fs::create_directories(out_dir);
  const fs::path root = fs::canonical(out_dir);
  // Walk down one component at a time, resolving each existing one through symlinks before
  // creating anything below it: a symlink planted inside the output directory must not lead
  // a write (or a create_directories) out of it.
  fs::path current = root;
  const fs::path normal = relative.lexically_normal();
  for (auto it = normal.begin(); it != normal.end(); ++it) {
    const bool last = std::next(it) == normal.end();
    fs::path next = current / *it;
    if (fs::exists(fs::symlink_status(next))) {
      const fs::path resolved = resolve_links(next);
      if (!inside(root, resolved) && resolved != root)
        throw std::invalid_argument("'" + relative.string() +
                                    "': leads outside the output directory through a symbolic link");
      if (!last && !fs::is_directory(resolved))
        throw std::invalid_argument("'" + relative.string() + "': '" + it->string() +
                                    "' exists and is not a directory");
      if (last && fs::is_directory(resolved))
        throw std::invalid_argument("'" + relative.string() + "': is an existing directory");
      current = resolved;
    } else {
      if (!last) fs::create_directory(next);
      current = next;
    }
  }
  return current;
}

}  // namespace sutura::app
