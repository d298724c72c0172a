#include "session_ops.hpp"

#include <cctype>

#include "sutura/app/output_paths.hpp"

namespace sutura::app::detail {

// Output paths are checked while parsing so a hostile or mistyped path is refused before
// anything runs.
std::filesystem::path output_file(Fields& f, const std::string& key,
                                  const std::vector<std::string>& extensions) {
  std::string value = f.required_string(key);
  std::filesystem::path p(value);
  if (std::string why = output_path_problem(p); !why.empty()) f.fail(key, why);
  std::string ext = p.extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const auto& e : extensions)
    if (ext == e) return p;
  std::string list;
  for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
  f.fail(key, "'" + value + "' must end in " + list);
}

std::string object_name(Fields& f) {
  std::string name = f.required_string("object");
  for (char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'))
      f.fail("object", "'" + name + "' may contain only letters, digits, '_' and '-'");
  }
  return name;
}

engine::Vec3 vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }



}  // namespace sutura::app::detail
