#include "sutura/app/session.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "session_ops.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::app {

using detail::Fields;
using nlohmann::json;

namespace {

std::string describe(const std::string& file, int line, const std::string& op,
                     const std::string& field, const std::string& problem) {
  std::ostringstream s;
  s << file;
  if (line > 0) s << ':' << line;
  s << ": ";
  if (!op.empty()) s << "op '" << op << "': ";
  if (!field.empty()) s << "field '" << field << "': ";
  s << problem;
  return s.str();
}

}  // namespace

SessionError::SessionError(std::string file, int line, std::string op, std::string field,
                           const std::string& problem)
    : std::runtime_error(describe(file, line, op, field, problem)),
      file_(std::move(file)),
      line_(line),
      op_(std::move(op)),
      field_(std::move(field)) {}

const std::vector<std::string>& known_ops() {
  static const std::vector<std::string> ops = [] {
    std::vector<std::string> names;
    for (const auto* family : {&detail::scene_op_parsers(), &detail::simulation_op_parsers(),
                                &detail::surgery_op_parsers()})
      for (const auto& p : *family) names.emplace_back(p.name);
    return names;
  }();
  return ops;
}

Action parse_action(const json& j, const std::filesystem::path& file, int line_no, int version) {
  const std::string fname = file.string();
  if (!j.is_object()) throw SessionError(fname, line_no, "", "", "each line must be a JSON object");
  if (!j.contains("op")) throw SessionError(fname, line_no, "", "op", "missing");
  if (!j["op"].is_string()) throw SessionError(fname, line_no, "", "op", "must be a string");
  const std::string name = j["op"].get<std::string>();
  Fields f(j, fname, line_no, name, version);
  f.required_string("op");
  f.optional_string("note", "");  // free text for the reader of the session
  Action action;
  action.line = line_no;
  action.name = name;
  action.source = j;
  try {
    const detail::OpParser* parser = nullptr;
    for (const auto* family : {&detail::scene_op_parsers(), &detail::simulation_op_parsers(),
                                &detail::surgery_op_parsers()})
      for (const auto& p : *family)
        if (name == p.name) parser = &p;
    if (parser == nullptr) {
      std::string list;
      for (const auto& o : known_ops()) list += (list.empty() ? "" : ", ") + o;
      throw SessionError(fname, line_no, name, "op", "unknown op (known: " + list + ")");
    }
    action.op = parser->parse(f, file);
  } catch (const engine::InvalidArgument& e) {
    throw SessionError(fname, line_no, name, "", e.what());
  }
  f.finish();
  return action;
}

Session parse_session(const std::string& text, const std::filesystem::path& file) {
  const std::string fname = file.string();
  Session session;
  session.file = file;
  std::istringstream in(text);
  std::string raw;
  int line_no = 0;
  bool have_header = false;
  while (std::getline(in, raw)) {
    ++line_no;
    if (!raw.empty() && raw.back() == '\r') raw.pop_back();
    if (raw.find_first_not_of(" \t") == std::string::npos) continue;  // blank line
    json j;
    // Duplicate keys are an error (nlohmann keeps the last silently: {"op": "material", ...,
    // "op": "export"} would run an export). One set of keys per open object.
    std::vector<std::vector<std::string>> keys;
    std::string duplicate;
    const json::parser_callback_t no_duplicates = [&](int, json::parse_event_t event, json& parsed) {
      if (event == json::parse_event_t::object_start) keys.emplace_back();
      else if (event == json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
      else if (event == json::parse_event_t::key && !keys.empty()) {
        const std::string k = parsed.get<std::string>();
        if (std::find(keys.back().begin(), keys.back().end(), k) != keys.back().end() && duplicate.empty())
          duplicate = k;
        keys.back().push_back(k);
      }
      return true;
    };
    try {
      j = json::parse(raw, no_duplicates);
    } catch (const json::out_of_range& e) {
      // 406: a number such as 1e999 that no double holds.
      throw SessionError(fname, line_no, "", "",
                         std::string("a number is out of range (no finite double holds it): ") + e.what());
    } catch (const json::exception& e) {
      throw SessionError(fname, line_no, "", "", std::string("not valid JSON: ") + e.what());
    }
    if (!duplicate.empty())
      throw SessionError(fname, line_no, "", duplicate, "appears twice in one object; each key once");
    if (!j.is_object()) throw SessionError(fname, line_no, "", "", "each line must be a JSON object");

    if (!have_header) {
      Fields h(j, fname, line_no, "");
      if (!h.has("format"))
        h.fail("format", "the first line must be the header {\"format\": \"sutura-session\", \"version\": 1}");
      if (h.required_string("format") != "sutura-session")
        h.fail("format", "must be \"sutura-session\"");
      session.version = h.optional_int("version", 0, 1, 1000000);
      if (session.version == 0) h.fail("version", "missing");
      if (session.version > kSessionFormatVersion)
        h.fail("version", "version " + std::to_string(session.version) +
                              " is newer than this build reads (" +
                              std::to_string(kSessionFormatVersion) + ")");
      session.description = h.optional_string("description", "");
      h.optional_string("units", "mm");
      h.finish();
      have_header = true;
      continue;
    }

    session.actions.push_back(parse_action(j, file, line_no, session.version));
  }
  if (!have_header) throw SessionError(fname, 0, "", "", "empty session: no header line");
  return session;
}

Session load_session(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(st)) throw SessionError(file.string(), 0, "", "", "no such file");
  if (std::filesystem::is_directory(st))
    throw SessionError(file.string(), 0, "", "", "is a directory, not a session file");
  // Checked before opening: opening a FIFO blocks until a writer comes, and a device such as
  // /dev/zero never ends.
  if (!std::filesystem::is_regular_file(st))
    throw SessionError(file.string(), 0, "", "",
                       "is not a regular file (a device, FIFO or socket); sessions are read from files");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SessionError(file.string(), 0, "", "", "cannot be opened for reading");
  // Read in chunks, at most one chunk past kMaxSessionBytes whatever the file grows to
  // meanwhile, so that a small file costs a small buffer.
  std::string text;
  std::array<char, 1 << 16> chunk;
  while (in.read(chunk.data(), std::streamsize(chunk.size())) || in.gcount() > 0) {
    text.append(chunk.data(), std::size_t(in.gcount()));
    if (text.size() > kMaxSessionBytes)
      throw SessionError(file.string(), 0, "", "",
                         "larger than " + std::to_string(kMaxSessionBytes >> 20) +
                             " MiB, the size limit of a session file");
  }
  return parse_session(text, file);
}

engine::ShellMaterial MaterialFields::applied_to(engine::ShellMaterial base) const {
  if (youngs_modulus) base.youngs_modulus = *youngs_modulus;
  if (poisson_ratio) base.poisson_ratio = *poisson_ratio;
  if (thickness) base.thickness = *thickness;
  if (density) base.density = *density;
  if (drilling_factor) base.drilling_factor = *drilling_factor;
  return base;
}

}  // namespace sutura::app
