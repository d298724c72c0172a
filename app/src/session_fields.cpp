#include "session_fields.hpp"

#include <cmath>

namespace sutura::app::detail {

using nlohmann::json;

namespace {
std::string type_name(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_boolean()) return "a boolean";
  if (v.is_number()) return "a number";
  if (v.is_string()) return "a string";
  if (v.is_array()) return "an array";
  return "an object";
}
}  // namespace

Fields::Fields(const json& object, std::string file, int line, std::string op, int format_version)
    : object_(object),
      file_(std::move(file)),
      line_(line),
      op_(std::move(op)),
      format_version_(format_version) {}

bool Fields::has(const std::string& key) const { return object_.contains(key); }

std::string Fields::qualified(const std::string& key) const { return prefix_ + key; }

void Fields::fail(const std::string& field, const std::string& problem) const {
  throw SessionError(file_, line_, op_, field.empty() ? field : qualified(field), problem);
}

const json& Fields::take(const std::string& key) {
  used_.insert(key);
  return object_.at(key);
}

std::string Fields::required_string(const std::string& key) {
  if (!has(key)) fail(key, "missing (a string is required)");
  const json& v = take(key);
  if (!v.is_string()) fail(key, "must be a string, got " + type_name(v));
  auto s = v.get<std::string>();
  if (s.empty()) fail(key, "must not be empty");
  return s;
}

std::string Fields::optional_string(const std::string& key, const std::string& fallback) {
  if (!has(key)) return fallback;
  return required_string(key);
}

std::string Fields::optional_choice(const std::string& key, const std::string& fallback,
                                    const std::vector<std::string>& choices) {
  std::string s = optional_string(key, fallback);
  for (const auto& c : choices)
    if (c == s) return s;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(key, "'" + s + "' is not one of: " + list);
}

double Fields::optional_number(const std::string& key, double fallback) {
  if (!has(key)) return fallback;
  const json& v = take(key);
  if (!v.is_number()) fail(key, "must be a number, got " + type_name(v));
  double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "must be finite");
  return d;
}

double Fields::optional_positive(const std::string& key, double fallback) {
  double d = optional_number(key, fallback);
  if (!(d > 0.0)) fail(key, "must be greater than 0, got " + json(d).dump());
  return d;
}

int Fields::optional_int(const std::string& key, int fallback, int min, int max) {
  if (!has(key)) return fallback;
  const json& v = take(key);
  if (!v.is_number()) fail(key, "must be a whole number, got " + type_name(v));
  double d = v.get<double>();
  if (d != std::floor(d)) fail(key, "must be a whole number, got " + v.dump());
  if (d < min || d > max)
    fail(key, "must be between " + std::to_string(min) + " and " + std::to_string(max) +
                  ", got " + v.dump());
  return static_cast<int>(d);
}

bool Fields::optional_bool(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const json& v = take(key);
  if (!v.is_boolean()) fail(key, "must be true or false, got " + type_name(v));
  return v.get<bool>();
}

Vec3d Fields::required_vec3(const std::string& key) {
  if (!has(key)) fail(key, "missing (an array of 3 numbers is required)");
  const json& v = take(key);
  if (!v.is_array() || v.size() != 3) fail(key, "must be an array of 3 numbers");
  Vec3d out{};
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) fail(key, "must be an array of 3 numbers");
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "must be finite");
  }
  return out;
}

std::optional<Vec3d> Fields::optional_vec3(const std::string& key) {
  if (!has(key)) return std::nullopt;
  return required_vec3(key);
}

std::optional<std::array<double, 2>> Fields::optional_range(const std::string& key) {
  if (!has(key)) return std::nullopt;
  const json& v = take(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    fail(key, "must be an array [min, max] of 2 numbers");
  std::array<double, 2> r{v[0].get<double>(), v[1].get<double>()};
  if (!std::isfinite(r[0]) || !std::isfinite(r[1]) || !(r[0] < r[1]))
    fail(key, "must be finite with min < max");
  return r;
}

std::vector<std::string> Fields::optional_string_list(const std::string& key) {
  if (!has(key)) return {};
  const json& v = take(key);
  if (!v.is_array()) fail(key, "must be an array of strings");
  std::vector<std::string> out;
  for (const auto& e : v) {
    if (!e.is_string() || e.get<std::string>().empty())
      fail(key, "must be an array of non-empty strings");
    out.push_back(e.get<std::string>());
  }
  return out;
}

std::optional<Fields> Fields::optional_object(const std::string& key) {
  if (!has(key)) return std::nullopt;
  const json& v = take(key);
  if (!v.is_object()) fail(key, "must be an object, got " + type_name(v));
  Fields nested(v, file_, line_, op_, format_version_);
  nested.prefix_ = qualified(key) + ".";
  return nested;
}

std::vector<Fields> Fields::object_list(const std::string& key) {
  if (!has(key)) fail(key, "missing (an array of objects is required)");
  const json& v = take(key);
  if (!v.is_array() || v.empty()) fail(key, "must be a non-empty array of objects");
  std::vector<Fields> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string name = key + "[" + std::to_string(i) + "]";
    if (!v[i].is_object()) fail(name, "must be an object, got " + type_name(v[i]));
    Fields nested(v[i], file_, line_, op_, format_version_);
    nested.prefix_ = qualified(name) + ".";
    out.push_back(std::move(nested));
  }
  return out;
}

const json* Fields::raw(const std::string& key) {
  if (!has(key)) return nullptr;
  return &take(key);
}

std::vector<Vec3d> Fields::vec3_list(const std::string& key) {
  const json* v = raw(key);
  if (v == nullptr) fail(key, "missing (an array of [x, y, z] points is required)");
  if (!v->is_array() || v->empty()) fail(key, "must be a non-empty array of [x, y, z] points");
  std::vector<Vec3d> out;
  for (const auto& e : *v) {
    if (!e.is_array() || e.size() != 3 || !e[0].is_number() || !e[1].is_number() ||
        !e[2].is_number())
      fail(key, "must be a non-empty array of [x, y, z] points");
    out.push_back({e[0].get<double>(), e[1].get<double>(), e[2].get<double>()});
  }
  return out;
}

void Fields::finish() const {
  for (const auto& [key, value] : object_.items()) {
    if (used_.count(key) == 0) fail(key, "unknown field");
  }
}

}  // namespace sutura::app::detail
