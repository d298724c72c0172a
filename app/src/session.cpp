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
      f.optional_choice("shape", "", {"tube", "strip", "cylinder_panel", "ellipse", "diamond", "triangle"});
  if (shape.empty())
    f.fail("shape", "missing (tube, strip, cylinder_panel, ellipse, diamond or triangle)");
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
  } else if (shape == "cylinder_panel") {
    engine::CylinderPanelParams p;
    p.radius = f.optional_positive("radius", p.radius);
    p.length = f.optional_positive("length", p.length);
    if (auto a = f.optional_range("angle_deg")) {
      p.angle_start_deg = (*a)[0];
      p.angle_end_deg = (*a)[1];
      if ((*a)[1] - (*a)[0] >= 360.0) f.fail("angle_deg", "must span less than 360 degrees");
    }
    p.segments_around = f.optional_int("segments_around", p.segments_around, 1, 100000);
    p.segments_along = f.optional_int("segments_along", p.segments_along, 1, 100000);
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
      f.optional_choice("field", "none", {"none", "displacement", "x", "y", "z", "membrane_strain",
                                          "bending", "energy_density"});
  static const std::map<std::string, Field> fields = {{"none", Field::None},
                                                      {"displacement", Field::Displacement},
                                                      {"x", Field::X},
                                                      {"y", Field::Y},
                                                      {"z", Field::Z},
                                                      {"membrane_strain", Field::MembraneStrain},
                                                      {"bending", Field::Bending},
                                                      {"energy_density", Field::EnergyDensity}};
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

engine::Vec3 vec(const Vec3f& v) { return {v[0], v[1], v[2]}; }

std::vector<std::string> object_list(Fields& f) {
  auto names = f.optional_string_list("objects");
  return names;
}

// Exactly one of: vertices, nearest, box, plane, boundary.
VertexSelection parse_selection(Fields& f) {
  const std::vector<std::string> keys = {"vertices", "nearest", "box", "plane", "boundary"};
  int count = 0;
  for (const auto& k : keys) count += f.has(k) ? 1 : 0;
  if (count != 1)
    f.fail("", "give exactly one vertex selection: vertices, nearest, box, plane or boundary");
  VertexSelection sel;
  if (const auto* v = f.raw("vertices")) {
    engine::SelectIds ids;
    if (!v->is_array() || v->empty()) f.fail("vertices", "must be a non-empty array of vertex ids");
    for (const auto& e : *v) {
      if (!e.is_number_integer() || e.get<long long>() < 0 || e.get<long long>() > INT32_MAX)
        f.fail("vertices", "must be a non-empty array of vertex ids (whole numbers >= 0)");
      ids.ids.emplace_back(static_cast<std::int32_t>(e.get<long long>()));
    }
    sel.engine = ids;
  } else if (f.has("nearest")) {
    engine::SelectNearest n;
    for (const auto& p : f.vec3_list("nearest")) n.points.push_back(vec(p));
    sel.engine = n;
  } else if (auto box = f.optional_object("box")) {
    engine::SelectBox b{vec(box->required_vec3("min")), vec(box->required_vec3("max"))};
    if (!(b.min.array() <= b.max.array()).all()) box->fail("max", "must be >= min componentwise");
    box->finish();
    sel.engine = b;
  } else if (auto plane = f.optional_object("plane")) {
    engine::SelectPlaneBand p;
    p.point = vec(plane->required_vec3("point"));
    p.normal = vec(plane->required_vec3("normal"));
    if (p.normal.isZero()) plane->fail("normal", "must not be the zero vector");
    p.distance = plane->optional_number("distance", 1e-6);
    if (p.distance < 0.0) plane->fail("distance", "must be >= 0");
    plane->finish();
    sel.engine = p;
  } else {
    const auto* b = f.raw("boundary");
    std::vector<int> loops;
    if (b->is_string() && b->get<std::string>() == "all") {
    } else if (b->is_array() && !b->empty()) {
      for (const auto& e : *b) {
        if (!e.is_number_integer() || e.get<long long>() < 0 || e.get<long long>() > 1000000)
          f.fail("boundary", "must be \"all\" or an array of boundary loop indices");
        loops.push_back(static_cast<int>(e.get<long long>()));
      }
    } else {
      f.fail("boundary", "must be \"all\" or an array of boundary loop indices");
    }
    sel.boundary_loops = loops;
  }
  return sel;
}

MaterialOp parse_material(Fields& f) {
  MaterialOp op;
  op.object = object_name(f);
  auto& m = op.material;
  m.youngs_modulus = f.optional_positive("youngs_modulus", m.youngs_modulus);
  m.poisson_ratio = f.optional_number("poisson_ratio", m.poisson_ratio);
  if (m.poisson_ratio < 0.0 || m.poisson_ratio >= 0.5)
    f.fail("poisson_ratio", "must be in [0, 0.5)");
  m.thickness = f.optional_positive("thickness", m.thickness);
  m.density = f.optional_positive("density", m.density);
  m.drilling_factor = f.optional_positive("drilling_factor", m.drilling_factor);
  return op;
}

ConstrainOp parse_constrain(Fields& f) {
  ConstrainOp op;
  op.object = object_name(f);
  op.where = parse_selection(f);
  auto dofs = f.optional_string_list("dofs");
  op.dofs = dofs.empty() ? engine::kAllDofs : engine::parse_dofs(dofs);
  return op;
}

ForceOp parse_force(Fields& f) {
  ForceOp op;
  op.object = object_name(f);
  op.where = parse_selection(f);
  if (!f.has("force") && !f.has("moment")) f.fail("force", "give force and/or moment");
  if (auto v = f.optional_vec3("force")) op.force = vec(*v);
  if (auto v = f.optional_vec3("moment")) op.moment = vec(*v);
  op.per_node = f.optional_choice("distribution", "total", {"total", "per_node"}) == "per_node";
  return op;
}

LineLoadOp parse_line_load(Fields& f) {
  LineLoadOp op;
  op.object = object_name(f);
  op.where = parse_selection(f);
  op.force_per_length = vec(f.required_vec3("force_per_length"));
  return op;
}

PressureOp parse_pressure(Fields& f) {
  PressureOp op;
  op.object = object_name(f);
  op.pressure = f.optional_number("pressure", 0.0);
  if (!f.has("pressure") || op.pressure == 0.0) f.fail("pressure", "missing or zero (MPa)");
  return op;
}

BodyForceOp parse_body_force(Fields& f) {
  BodyForceOp op;
  op.object = object_name(f);
  if (f.has("per_area") == f.has("acceleration"))
    f.fail("per_area", "give exactly one of per_area (N/mm^2) or acceleration (mm/s^2)");
  if (auto v = f.optional_vec3("per_area")) op.per_area = vec(*v);
  if (auto v = f.optional_vec3("acceleration")) op.acceleration = vec(*v);
  return op;
}

engine::LinearSolverKind linear_solver(Fields& f, engine::LinearSolverKind fallback) {
  return engine::parse_linear_solver(
      f.optional_choice("linear_solver", engine::to_string(fallback), {"cholmod", "ldlt", "pcg"}));
}

SolveOp parse_solve(Fields& f) {
  SolveOp op;
  op.objects = object_list(f);
  op.model = f.optional_choice("model", op.model, {"corotational", "discrete"});
  op.load_factor = f.optional_positive("load_factor", op.load_factor);
  if (op.load_factor > 1.0) f.fail("load_factor", "must be in (0, 1]");
  auto& p = op.params;
  p.load_steps = f.optional_int("load_steps", p.load_steps, 1, 100000);
  p.tolerance = f.optional_positive("tolerance", p.tolerance);
  if (p.tolerance >= 1.0) f.fail("tolerance", "must be below 1");
  p.max_iterations = f.optional_int("max_iterations", p.max_iterations, 1, 10000);
  p.line_search = f.optional_bool("line_search", p.line_search);
  p.linear_solver = linear_solver(f, p.linear_solver);
  p.linear = f.optional_choice("analysis", "nonlinear", {"nonlinear", "linear"}) == "linear";
  return op;
}

SimulateOp parse_simulate(Fields& f) {
  SimulateOp op;
  op.objects = object_list(f);
  op.model = f.optional_choice("model", op.model, {"corotational", "discrete"});
  auto& p = op.params;
  p.dt = f.optional_positive("dt", p.dt);
  p.steps = f.optional_int("steps", p.steps, 1, 10000000);
  p.mass_damping = f.optional_number("mass_damping", p.mass_damping);
  if (p.mass_damping < 0.0) f.fail("mass_damping", "must be >= 0");
  p.stiffness_damping = f.optional_number("stiffness_damping", p.stiffness_damping);
  if (p.stiffness_damping < 0.0) f.fail("stiffness_damping", "must be >= 0");
  p.tolerance = f.optional_positive("tolerance", p.tolerance);
  if (p.tolerance >= 1.0) f.fail("tolerance", "must be below 1");
  p.max_iterations = f.optional_int("max_iterations", p.max_iterations, 1, 1000);
  p.linear_solver = linear_solver(f, p.linear_solver);
  return op;
}

ProbeOp parse_probe(Fields& f) {
  ProbeOp op;
  op.object = object_name(f);
  op.name = f.required_string("name");
  op.point = vec(f.required_vec3("point"));
  return op;
}

CheckOp parse_check(Fields& f) {
  CheckOp op;
  op.probe = f.required_string("probe");
  op.quantity = f.optional_choice("quantity", "", {"ux", "uy", "uz", "rx", "ry", "rz", "|u|"});
  if (op.quantity.empty()) f.fail("quantity", "missing (ux, uy, uz, rx, ry, rz or |u|)");
  if (!f.has("value")) f.fail("value", "missing");
  op.value = f.optional_number("value", 0.0);
  op.rel_tol = f.optional_number("rel_tol", 0.0);
  op.abs_tol = f.optional_number("abs_tol", 0.0);
  if (op.rel_tol < 0.0) f.fail("rel_tol", "must be >= 0");
  if (op.abs_tol < 0.0) f.fail("abs_tol", "must be >= 0");
  if (op.rel_tol == 0.0 && op.abs_tol == 0.0) f.fail("rel_tol", "give rel_tol and/or abs_tol");
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
  static const std::vector<std::string> ops = {
      "generate", "load",     "snapshot",   "export", "report", "material", "constrain", "force",
      "line_load", "pressure", "body_force", "solve",  "simulate", "probe", "check"};
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
      else if (name == "material") action.op = parse_material(f);
      else if (name == "constrain") action.op = parse_constrain(f);
      else if (name == "force") action.op = parse_force(f);
      else if (name == "line_load") action.op = parse_line_load(f);
      else if (name == "pressure") action.op = parse_pressure(f);
      else if (name == "body_force") action.op = parse_body_force(f);
      else if (name == "solve") action.op = parse_solve(f);
      else if (name == "simulate") action.op = parse_simulate(f);
      else if (name == "probe") action.op = parse_probe(f);
      else if (name == "check") action.op = parse_check(f);
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
