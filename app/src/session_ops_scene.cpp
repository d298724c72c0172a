// Parsers of the scene ops: generate, load, snapshot, export, export_patch_template, report,
// plan_report.
#include <algorithm>
#include <cmath>
#include <map>

#include "session_defaults.hpp"
#include "session_ops.hpp"

namespace sutura::app::detail {

namespace {

GenerateOp parse_generate(Fields& f) {
  GenerateOp op;
  op.object = object_name(f);
  op.append = f.optional_bool("append", false);
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
  if (auto p = f.optional_object("prepare")) {
    PrepareSpec spec;
    spec.params = detail::prepare_defaults(f.format_version());
    if (p->has("edge_length")) spec.params.edge_length = p->optional_positive("edge_length", 1.0);
    spec.params.smoothing_iterations = p->optional_int("smoothing", spec.params.smoothing_iterations, 0, 100);
    p->finish();
    op.prepare = spec;
  }
  if (f.has("landmarks")) {
    if (op.prepare) f.fail("landmarks", "a prepared mesh names its ends itself (end_1, end_2, ...)");
    std::filesystem::path l(f.required_string("landmarks"));
    op.landmarks = l.is_absolute() ? l : session_file.parent_path() / l;
  }
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
  auto norm = [](const Vec3d& v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; };
  if (norm(cam.up) == 0.0) c.fail("up", "must not be the zero vector");
  if (norm(cam.view) == 0.0) c.fail("view", "must not be the zero vector");
  if (cam.eye) {
    Vec3d d{(*cam.target)[0] - (*cam.eye)[0], (*cam.target)[1] - (*cam.eye)[1],
            (*cam.target)[2] - (*cam.eye)[2]};
    if (norm(d) == 0.0) c.fail("eye", "eye and target must differ");
  }
  c.finish();
  return cam;
}

ClipSpec parse_clip(Fields& c) {
  ClipSpec clip;
  clip.point = c.required_vec3("point");
  clip.normal = c.required_vec3("normal");
  // Drawn in single precision, with n.p formed there: the point must stay far inside float.
  for (double x : clip.point)
    if (!(std::abs(x) <= 1e30)) c.fail("point", "must be within +-1e30 mm");
  // Scaled by its largest component first, so that any finite, non-zero length normalises.
  const double big = std::max({std::abs(clip.normal[0]), std::abs(clip.normal[1]), std::abs(clip.normal[2])});
  if (!(big > 0.0)) c.fail("normal", "must not be the zero vector");
  for (double& x : clip.normal) x /= big;
  const double len = std::sqrt(clip.normal[0] * clip.normal[0] + clip.normal[1] * clip.normal[1] +
                               clip.normal[2] * clip.normal[2]);
  for (double& x : clip.normal) x /= len;
  c.finish();
  return clip;
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
  op.marks = f.optional_bool("marks", op.marks);
  op.compare_rest = f.optional_choice("compare", "before", {"before", "rest"}) == "rest";
  if (op.compare_rest && !op.side_by_side) f.fail("compare", "needs side_by_side: true");
  if (auto clip = f.optional_object("clip")) op.clip = parse_clip(*clip);
  return op;
}

ExportOp parse_export(Fields& f) {
  ExportOp op;
  op.object = object_name(f);
  op.file = output_file(f, "file", {".obj", ".ply", ".stl"});
  return op;
}

ExportPatchTemplateOp parse_export_patch_template(Fields& f) {
  ExportPatchTemplateOp op;
  op.object = object_name(f);
  op.file = output_file(f, "file", {".svg", ".pdf"});
  op.patch = f.optional_int("patch", 1, 1, 1000);
  op.proximal = vec(f.required_vec3("proximal"));
  op.bite_spacing = f.optional_positive("bite_spacing", op.bite_spacing);
  if (!(op.bite_spacing >= 0.1 && op.bite_spacing <= 20.0)) f.fail("bite_spacing", "must be in [0.1, 20] mm");
  op.seam_allowance = f.optional_number("seam_allowance", op.seam_allowance);
  if (!(op.seam_allowance >= 0.0 && op.seam_allowance <= 20.0))
    f.fail("seam_allowance", "must be in [0, 20] mm");
  return op;
}

ReportOp parse_report(Fields& f) {
  ReportOp op;
  op.file = output_file(f, "file", {".json"});
  return op;
}

PlanReportOp parse_plan_report(Fields& f) {
  PlanReportOp op;
  op.file = output_file(f, "file", {".html"});
  if (f.has("pdf")) {
    op.pdf = output_file(f, "pdf", {".pdf"});
  } else {
    op.pdf = op.file;
    op.pdf.replace_extension(".pdf");
  }
  op.view_width = f.optional_int("view_width", op.view_width, 200, 2000);
  op.view_height = f.optional_int("view_height", op.view_height, 200, 2000);
  return op;
}

}  // namespace

const std::vector<OpParser>& scene_op_parsers() {
  static const std::vector<OpParser> parsers = {
      {"generate", [](Fields& f, const std::filesystem::path&) -> Op { return parse_generate(f); }},
      {"load", [](Fields& f, const std::filesystem::path& file) -> Op { return parse_load(f, file); }},
      {"snapshot", [](Fields& f, const std::filesystem::path&) -> Op { return parse_snapshot(f); }},
      {"export", [](Fields& f, const std::filesystem::path&) -> Op { return parse_export(f); }},
      {"export_patch_template",
       [](Fields& f, const std::filesystem::path&) -> Op { return parse_export_patch_template(f); }},
      {"report", [](Fields& f, const std::filesystem::path&) -> Op { return parse_report(f); }},
      {"plan_report", [](Fields& f, const std::filesystem::path&) -> Op { return parse_plan_report(f); }},
  };
  return parsers;
}

}  // namespace sutura::app::detail
