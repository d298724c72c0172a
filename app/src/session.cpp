#include "sutura/app/session.hpp"

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
    try {
      j = json::parse(raw);
    } catch (const json::parse_error& e) {
      throw SessionError(fname, line_no, "", "", std::string("not valid JSON: ") + e.what());
    }
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
  if (!std::filesystem::exists(file, ec))
    throw SessionError(file.string(), 0, "", "", "no such file");
  if (std::filesystem::is_directory(file, ec))
    throw SessionError(file.string(), 0, "", "", "is a directory, not a session file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SessionError(file.string(), 0, "", "", "cannot be opened for reading");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_session(ss.str(), file);
}

}  // namespace sutura::app
