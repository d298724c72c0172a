#pragma once
// Typed, checked access to the fields of one session line. Every getter names the field and
// the line in its error; finish() rejects fields nobody asked for (typos).
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "sutura/app/session.hpp"

namespace sutura::app::detail {

class Fields {
 public:
  Fields(const nlohmann::json& object, std::string file, int line, std::string op,
         int format_version = kSessionFormatVersion);

  /// The session format version of the line (defaults that changed depend on it).
  [[nodiscard]] int format_version() const { return format_version_; }

  [[nodiscard]] bool has(const std::string& key) const;
  [[noreturn]] void fail(const std::string& field, const std::string& problem) const;

  std::string required_string(const std::string& key);
  std::string optional_string(const std::string& key, const std::string& fallback);
  /// A string that is one of `choices`.
  std::string optional_choice(const std::string& key, const std::string& fallback,
                              const std::vector<std::string>& choices);
  double optional_number(const std::string& key, double fallback);
  /// A number > 0 (lengths, sizes).
  double optional_positive(const std::string& key, double fallback);
  /// A whole number in [min, max].
  int optional_int(const std::string& key, int fallback, int min, int max);
  bool optional_bool(const std::string& key, bool fallback);
  Vec3d required_vec3(const std::string& key);
  std::optional<Vec3d> optional_vec3(const std::string& key);
  /// [min, max] with min < max, both finite.
  std::optional<std::array<double, 2>> optional_range(const std::string& key);
  std::vector<std::string> optional_string_list(const std::string& key);
  /// A nested object, checked with its own Fields (its errors say "camera.eye" etc.).
  std::optional<Fields> optional_object(const std::string& key);

  /// A required non-empty array of objects, each checked with its own Fields (errors say
  /// "sutures[1].a.from" etc.). Call finish() on each.
  std::vector<Fields> object_list(const std::string& key);
  /// The raw value of an optional field (marked as used), or nullptr.
  const nlohmann::json* raw(const std::string& key);
  /// An array of 3-vectors.
  std::vector<Vec3d> vec3_list(const std::string& key);

  /// Throws if the line has a field no getter asked for.
  void finish() const;

 private:
  const nlohmann::json& take(const std::string& key);
  [[nodiscard]] std::string qualified(const std::string& key) const;

  const nlohmann::json& object_;
  std::string file_;
  int line_;
  std::string op_;
  std::string prefix_;  // "camera." for nested objects
  int format_version_;
  std::set<std::string> used_;
};

}  // namespace sutura::app::detail
