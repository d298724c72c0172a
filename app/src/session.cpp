#include "sutura/app/session.hpp"

#include <fstream>
#include <functional>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "session_fields.hpp"
#include "sutura/app/output_paths.hpp"
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

GenerateOp parse_generate(Fields& f) {
  GenerateOp op;
  op.object = object_name(f);
  const std::string shape =
      f.optional_choice("shape", "", {"tube", "strip", "ellipse", "diamond", "triangle"});
  if (shape.empty()) f.fail("shape", "missing (tube, strip, ellipse, diamond or triangle)");
  if (shape == "tube") {
    engine::TubeParams p;
    p.radius = f.optional_positive("radius", p.radius);
    p.length = f.optional_positive("length", p.length);
    p.segments_around = f.optional_int("segments_around", p.segments_around, 3, 100000);
    p.segments_along = f.optional_int("segments_along", p.segments_along, 1, 100000);
    op.params = p;
  } else if (shape == "strip") {
    engine::StripParams p;
    p.length = f.optional_positive("length", p.length);
    p.width = f.optional_positive("width", p.width);
    p.segments_length = f.optional_int("segments_length", p.segments_length, 1, 100000);
    p.segments_width = f.optional_int("segments_width", p.segments_width, 1, 100000);
    op.params = p;
  } else {
    engine::PatchParams p;
    p.shape = engine::parse_patch_shape(shape);
    p.length = f.optional_positive("length", p.length);
    p.width = f.optional_positive("width", p.width);
    p.target_edge_length = f.optional_positive("edge_length", p.target_edge_length);
    if (p.target_edge_length > 0.5 * std::min(p.length, p.width))
      f.fail("edge_length", "must be at most half of the patch's length and width");
    op.params = p;
  }
  if (auto t = f.optional_vec3("translate")) op.translate = *t;
  return op;
}

LoadOp parse_load(Fields& f, const std::filesystem::path& session_file) {
  LoadOp op;
  op.object = object_name(f);
  std::filesystem::path p(f.required_string("file"));
  op.file = p.is_absolute() ? p : session_file.parent_path() / p;
  op.weld_tolerance = f.optional_number("weld_tolerance", op.weld_tolerance);
  if (op.weld_tolerance < 0.0 || op.weld_tolerance > 0.01)
    f.fail("weld_tolerance", "must be between 0 and 0.01 (fraction of the bounding-box diagonal)");
  return op;
}

CameraSpec parse_camera(Fields& c) {
  CameraSpec cam;
  cam.eye = c.optional_vec3("eye");
  cam.target = c.optional_vec3("target");
  if (cam.eye.has_value() != cam.target.has_value())
    c.fail(cam.eye ? "target" : "eye", "eye and target must be given together");
  if (auto up = c.optional_vec3("up")) cam.up = *up;
  if (auto view = c.optional_vec3("view")) cam.view = *view;
  if (cam.eye && c.has("view")) c.fail("view", "give either view or eye/target, not both");
  cam.fov_deg = c.optional_number("fov_deg", cam.fov_deg);
  if (!(cam.fov_deg > 1.0 && cam.fov_deg < 170.0)) c.fail("fov_deg", "must be between 1 and 170");
  auto norm = [](const Vec3f& v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; };
  if (norm(cam.up) == 0.0) c.fail("up", "must not be the zero vector");
  if (norm(cam.view) == 0.0) c.fail("view", "must not be the zero vector");
  if (cam.eye) {
    Vec3f d{(*cam.target)[0] - (*cam.eye)[0], (*cam.target)[1] - (*cam.eye)[1],
            (*cam.target)[2] - (*cam.eye)[2]};
    if (norm(d) == 0.0) c.fail("eye", "eye and target must differ");
  }
  c.finish();
  return cam;
}

SnapshotOp parse_snapshot(Fields& f) {
  SnapshotOp op;
  op.file = output_file(f, "file", {".png"});
  op.width = f.optional_int("width", op.width, 16, 8192);
  op.height = f.optional_int("height", op.height, 16, 8192);
  op.objects = f.optional_string_list("objects");
  const std::string field =
      f.optional_choice("field", "none", {"none", "displacement", "x", "y", "z"});
  static const std::map<std::string, Field> fields = {{"none", Field::None},
                                                      {"displacement", Field::Displacement},
                                                      {"x", Field::X},
                                                      {"y", Field::Y},
                                                      {"z", Field::Z}};
  op.field = fields.at(field);
  if (f.has("range") && op.field == Field::None) f.fail("range", "needs a colour field");
  op.range = f.optional_range("range");
  if (auto cam = f.optional_object("camera")) op.camera = parse_camera(*cam);
  op.side_by_side = f.optional_bool("side_by_side", op.side_by_side);
  op.wireframe = f.optional_bool("wireframe", op.wireframe);
  op.boundaries = f.optional_bool("boundaries", op.boundaries);
  return op;
}

ExportOp parse_export(Fields& f) {
  ExportOp op;
  op.object = object_name(f);
  op.file = output_file(f, "file", {".obj", ".ply", ".stl"});
  return op;
}

ReportOp parse_report(Fields& f) {
  ReportOp op;
  op.file = output_file(f, "file", {".json"});
  return op;
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
  static const std::vector<std::string> ops = {"generate", "load", "snapshot", "export",
                                               "report"};
  return ops;
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

    if (!j.contains("op")) throw SessionError(fname, line_no, "", "op", "missing");
    if (!j["op"].is_string()) throw SessionError(fname, line_no, "", "op", "must be a string");
    const std::string name = j["op"].get<std::string>();
    Fields f(j, fname, line_no, name);
    f.required_string("op");
    f.optional_string("note", "");  // free text for the reader of the session
    Action action;
    action.line = line_no;
    action.name = name;
    try {
      if (name == "generate") action.op = parse_generate(f);
      else if (name == "load") action.op = parse_load(f, file);
      else if (name == "snapshot") action.op = parse_snapshot(f);
      else if (name == "export") action.op = parse_export(f);
      else if (name == "report") action.op = parse_report(f);
      else {
        std::string list;
        for (const auto& o : known_ops()) list += (list.empty() ? "" : ", ") + o;
        throw SessionError(fname, line_no, name, "op", "unknown op (known: " + list + ")");
      }
    } catch (const engine::InvalidArgument& e) {
      throw SessionError(fname, line_no, name, "", e.what());
    }
    f.finish();
    session.actions.push_back(std::move(action));
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
