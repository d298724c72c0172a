// Execution of the scene ops (generate, load, snapshot, export, export_patch_template,
// report, plan_report) and the report.
#include "replay_run.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <tuple>

#include "sutura/engine/surgery/surface_attributes.hpp"
#include "sutura/app/output_paths.hpp"
#include "sutura/app/patch_template.hpp"
#include "sutura/app/plan_report.hpp"
#include "sutura/app/report.hpp"
#include "sutura/engine/atomic_file.hpp"
#include "sutura/engine/blas_kernels.hpp"
#include "sutura/engine/compute_threads.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "sutura/engine/patient/prepare.hpp"
#include "sutura/render/vector_page.hpp"

namespace sutura::app::detail {

namespace fs = std::filesystem;

fs::path Run::output(const fs::path& relative) {
  fs::path p = resolve_output_path(options.out_dir, relative);
  std::error_code ec;  // equivalent() is false, with ec set, when either file does not exist
  for (const fs::path& in : inputs)
    if (fs::equivalent(p, in, ec))
      throw std::invalid_argument("'" + relative.string() + "': is " +
                                  (in == session.file ? "the session being replayed"
                                                      : "an input of this run (" + in.string() + ")") +
                                  "; outputs never overwrite an input");
  outputs.push_back(relative.generic_string());
  return p;
}

namespace {

// The ends listed under `stem` in a landmarks file, `sutura generate`'s format:
// {"<stem>": {"ends": [{"name", "centre", "normal", "radius"}, ...]}, ...}. Every problem is
// an error naming the file and the field.
std::vector<engine::VesselEnd> read_named_ends(const std::filesystem::path& file, const std::string& stem) {
  const std::string where = "landmarks file " + file.string();
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec) throw std::runtime_error("cannot read " + where + ": " + ec.message());
  if (size > (std::uintmax_t{16} << 20)) throw std::runtime_error(where + " is larger than 16 MiB");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + where);
  json j;
  try {
    j = json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(where + " is not valid JSON (at byte " + std::to_string(e.byte) + ")");
  }
  if (!j.is_object() || !j.contains(stem))
    throw std::runtime_error(where + " has no entry '" + stem + "' (named after the mesh file)");
  const json* ends = j[stem].is_object() && j[stem].contains("ends") ? &j[stem]["ends"] : nullptr;
  if (!ends || !ends->is_array()) throw std::runtime_error(where + ": '" + stem + ".ends' must be an array");
  if (ends->size() > 1000) throw std::runtime_error(where + ": '" + stem + ".ends' lists more than 1000 ends");
  std::vector<engine::VesselEnd> out;
  for (std::size_t k = 0; k < ends->size(); ++k) {
    const json& e = (*ends)[k];
    const std::string field = stem + ".ends[" + std::to_string(k) + "]";
    const auto vec3 = [&](const char* key) {
      const json* v = e.is_object() && e.contains(key) ? &e[key] : nullptr;
      if (!v || !v->is_array() || v->size() != 3 || !(*v)[0].is_number() || !(*v)[1].is_number() ||
          !(*v)[2].is_number())
        throw std::runtime_error(where + ": '" + field + "." + key + "' must be 3 numbers");
      const engine::Vec3 p((*v)[0].get<double>(), (*v)[1].get<double>(), (*v)[2].get<double>());
      if (!p.allFinite()) throw std::runtime_error(where + ": '" + field + "." + key + "' must be finite");
      return p;
    };
    engine::VesselEnd end;
    if (!e.is_object() || !e.contains("name") || !e["name"].is_string() || e["name"].get<std::string>().empty())
      throw std::runtime_error(where + ": '" + field + ".name' must be a non-empty string");
    end.name = e["name"].get<std::string>();
    end.centre = vec3("centre");
    end.normal = vec3("normal");
    if (!e.contains("radius") || !e["radius"].is_number() || !(e["radius"].get<double>() > 0.0) ||
        !std::isfinite(e["radius"].get<double>()))
      throw std::runtime_error(where + ": '" + field + ".radius' must be a number > 0");
    end.radius = e["radius"].get<double>();
    out.push_back(std::move(end));
  }
  return out;
}
[[noreturn]] void no_object(const Workspace& w, const std::string& name) {
  throw std::runtime_error("no object named '" + name + "' (objects: " + w.names() + ")");
}
}  // namespace

const SceneObject& Run::object(const std::string& name) const {
  const SceneObject* o = workspace.find(name);
  if (o == nullptr) no_object(workspace, name);
  return *o;
}

SceneObject& Run::edit(const std::string& name) {
  SceneObject* o = workspace.edit(name);
  if (o == nullptr) no_object(workspace, name);
  return *o;
}

json Run::report(const std::string& status, const std::string& error, double total) const {
  json objects = json::object();
  for (const auto& o : workspace.objects()) objects[o.name] = object_summary(o);
  // Every op's warning, in order, so that none is missed among the actions.
  json warnings = json::array();
  for (const json& a : actions)
    if (a.contains("warning"))
      warnings.push_back({{"line", a.value("line", 0)}, {"op", a.value("op", "")}, {"warning", a["warning"]}});
  const engine::ComputeThreads threads = engine::compute_threads();
  json r = {{"sutura_version", SUTURA_VERSION},
            {"blas", engine::blas_kernels_in_use()},
            {"threads", {{"openmp", threads.openmp}, {"blas", threads.blas}}},
            {"session", session.file.generic_string()},
            {"description", session.description},
            {"status", status},
            {"actions", actions},
            {"objects", objects},
            {"outputs", outputs},
            {"probes", probes},
            {"checks", checks},
            {"measurements", measurements},
            {"warnings", warnings},
            {"total_seconds", total}};
  if (!error.empty()) r["error"] = error;
  return r;
}

bool Run::past_deadline() {
  if (!stopped && std::chrono::steady_clock::now() >= deadline) stopped = true;
  return stopped;
}

void Run::check_workspace_limits() const {
  const Limits& l = options.limits;
  std::size_t all = 0;
  for (const SceneObject& o : workspace.objects()) {
    all += o.mesh.num_faces();
    if (o.mesh.num_faces() > l.faces_per_object)
      throw std::runtime_error("object '" + o.name + "' has " + std::to_string(o.mesh.num_faces()) +
                               " faces, more than the limit of " + std::to_string(l.faces_per_object) +
                               " per object (--max-faces raises it)");
  }
  if (all > l.faces_in_all)
    throw std::runtime_error("the objects have " + std::to_string(all) + " faces in all, more than the limit of " +
                             std::to_string(l.faces_in_all) + " (--max-faces-in-all raises it)");
  if (workspace.objects().size() > l.objects)
    throw std::runtime_error(std::to_string(workspace.objects().size()) + " objects, more than the limit of " +
                             std::to_string(l.objects) + " (--max-objects raises it)");
}

void Run::write_report(const fs::path& relative, const json& r) {
  // Invalid UTF-8 (a file name is any bytes) becomes U+FFFD instead of failing the dump.
  engine::write_file_atomically(output(relative), r.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
}

json Run::execute(const GenerateOp& op) {
  remember();
  engine::SurfaceMesh mesh = std::visit(
      [](const auto& p) -> engine::SurfaceMesh {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, engine::TubeParams>) return engine::make_tube(p);
        else if constexpr (std::is_same_v<P, engine::StripParams>) return engine::make_strip(p);
        else if constexpr (std::is_same_v<P, engine::CylinderPanelParams>)
          return engine::make_cylinder_panel(p);
        else return engine::make_patch(p);
      },
      op.params);
  const engine::Vec3 t(op.translate[0], op.translate[1], op.translate[2]);
  if (!t.isZero()) {
    std::vector<engine::Vec3> moved = mesh.positions();
    for (auto& p : moved) p += t;
    mesh.set_positions(std::move(moved));
  }
  if (op.append) {
    SceneObject& obj = edit(op.object);
    engine::append_component(obj.mesh, obj.sim, mesh, mesh, obj.sim.materials.front());
    obj.before = obj.mesh;  // the new part is part of the pre-operative scene
    // ... and stress-free there (an unloaded object's measures go on for the old part).
    for (auto* v : {&obj.before_measures.membrane_strain, &obj.before_measures.bending_curvature,
                    &obj.before_measures.energy_density})
      if (!v->empty()) v->resize(obj.before.num_vertices(), 0.0);
    return {{"object", op.object}, {"appended", true}, {"vertices", obj.mesh.num_vertices()},
            {"faces", obj.mesh.num_faces()}};
  }
  const auto& obj = workspace.add(op.object, std::move(mesh));
  return {{"object", op.object}, {"vertices", obj.mesh.num_vertices()},
          {"faces", obj.mesh.num_faces()}};
}

json Run::execute(const LoadOp& op) {
  remember();
  engine::ImportOptions io;
  io.weld_tolerance = op.weld_tolerance;
  // Counted before the file is parsed: a file far above the limits is refused in a second.
  const Limits& l = options.limits;
  std::size_t present = 0;
  for (const SceneObject& o : workspace.objects()) present += o.mesh.num_faces();
  const std::size_t room = l.faces_in_all > present ? l.faces_in_all - present : 0;
  io.max_faces = std::max<std::size_t>(1, std::min(l.faces_per_object, room));
  // A segmentation export is far denser than what it becomes: its own limit is prepare's.
  if (op.prepare) io.max_faces = engine::kMaxPrepareInputFaces;
  inputs.push_back(op.file);
  engine::SurfaceMesh mesh;
  try {
    mesh = engine::load_mesh(op.file, io);
  } catch (const engine::MeshIoError& e) {
    if (e.kind() != engine::MeshIoError::Kind::TooLarge) throw;
    if (op.prepare)
      throw std::runtime_error(std::string(e.what()) + " faces that prepare takes; export the segmentation coarser");
    throw std::runtime_error(std::string(e.what()) +
                             (l.faces_per_object <= room ? " faces per object (--max-faces raises it)"
                                                         : " faces left of the limit of " + std::to_string(l.faces_in_all) +
                                                               " in all (--max-faces-in-all raises it)"));
  }
  json prepared = nullptr;
  std::vector<engine::VesselEnd> prepared_ends;
  if (op.prepare) {
    if (room == 0)
      throw std::runtime_error("prepare: no faces left of the limit of " + std::to_string(l.faces_in_all) +
                               " in all (--max-faces-in-all raises it)");
    engine::PrepareParams p = op.prepare->params;
    p.max_faces = std::max<std::size_t>(1, std::min(l.faces_per_object, room));
    engine::PrepareResult r = engine::prepare_vessel(mesh, p);
    for (const auto& e : r.ends) prepared_ends.push_back(e.end);
    json ends = json::array();
    for (const auto& e : r.ends)
      ends.push_back({{"name", e.end.name},
                      {"centre", {e.end.centre.x(), e.end.centre.y(), e.end.centre.z()}},
                      {"radius", e.end.radius},
                      {"from", e.was_cap ? "cap (opened)" : "open end"}});
    prepared = {{"input_faces", r.input_faces},
                {"ends", ends},
                {"dropped_components", r.dropped.size()},
                {"edge_length_mm", r.edge_length},
                {"min_angle_deg", r.min_angle_deg},
                {"hausdorff_to_input_mm", r.to_input.symmetric}};
    mesh = std::move(r.vessel);
  }
  std::vector<engine::VesselEnd> ends = std::move(prepared_ends);
  if (op.landmarks) {
    inputs.push_back(*op.landmarks);
    ends = read_named_ends(*op.landmarks, op.file.stem().string());
  }
  SceneObject& obj = workspace.add(op.object, std::move(mesh));
  obj.ends = std::move(ends);
  json names = json::array();
  for (const auto& loop : obj.mesh.boundary_loops()) names.push_back(end_name(obj, loop));
  json j = {{"object", op.object}, {"file", op.file.generic_string()},
            {"vertices", obj.mesh.num_vertices()}, {"faces", obj.mesh.num_faces()}};
  if (!obj.ends.empty()) j["end_names"] = names;
  if (op.prepare) j["prepared"] = prepared;
  return j;
}

json Run::execute(const SnapshotOp& op) {
  render::Image image = snapshots.render(op, workspace);
  const std::vector<std::uint8_t> png = render::encode_png(image);
  engine::write_file_atomically(
      output(op.file), std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
  return {{"file", op.file.generic_string()}, {"width", image.width}, {"height", image.height}};
}

json Run::execute(const ExportOp& op) {
  engine::save_mesh(object(op.object).mesh, output(op.file));
  return {{"object", op.object}, {"file", op.file.generic_string()}};
}

json Run::execute(const ExportPatchTemplateOp& op) {
  PatchTemplateOptions options;
  options.patch = op.patch;
  options.proximal = op.proximal;
  options.bite_spacing_mm = op.bite_spacing;
  options.seam_allowance_mm = op.seam_allowance;
  const std::string heading = "Sutura cutting template: " + session.file.filename().string() +
                              ", object '" + op.object + "', patch " + std::to_string(op.patch);
  const PatchTemplate t = make_patch_template(object(op.object), heading, options);
  std::string extension = op.file.extension().string();  // the parser took .svg or .pdf, any case
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string bytes = extension == ".pdf" ? render::to_pdf(t.page) : render::to_svg(t.page);
  engine::write_file_atomically(output(op.file), bytes);
  return {{"object", op.object},
          {"file", op.file.generic_string()},
          {"patch", op.patch},
          {"faces", t.faces},
          {"seam_length_mm", t.seam_length_mm},
          {"area_mm2", t.area_mm2},
          {"rest_seam_length_mm", t.rest_seam_length_mm},
          {"rest_area_mm2", t.rest_area_mm2},
          {"cut_length_mm", t.cut_length_mm},
          {"max_gap_mm", t.max_gap_mm},
          {"length_mm", t.length_mm},
          {"width_mm", t.width_mm},
          {"bites", t.bites},
          {"page_mm", {t.page.width_mm, t.page.height_mm}}};
}

json Run::execute(const PlanReportOp& op) {
  PlanReportSource source;
  source.session_file = session.file;
  source.description = session.description;
  std::tie(source.session_sha256, source.session_bytes) = file_sha256(session.file);
  source.program = program_version();
  const engine::ComputeThreads threads = engine::compute_threads();
  source.openmp_threads = threads.openmp;
  source.blas_threads = threads.blas;
  source.plan = &plan;
  source.measurements = &measurements;
  source.checks = &checks;
  source.workspace = &workspace;
  // Both paths are checked before anything is made or written.
  const std::filesystem::path html = output(op.file), pdf = output(op.pdf);
  const PlanReport r = make_plan_report(
      source, [this](const SnapshotOp& view) { return snapshots.render(view, workspace); }, op.view_width,
      op.view_height);
  engine::write_file_atomically(html, r.html);
  engine::write_file_atomically(pdf, r.pdf);
  json j = r.summary;
  j["file"] = op.file.generic_string();
  j["pdf"] = op.pdf.generic_string();
  return j;
}

json Run::execute(const ReportOp& op, double elapsed) {
  write_report(op.file, report("running", {}, elapsed));
  return {{"file", op.file.generic_string()}};
}

}  // namespace sutura::app::detail
