// Parsers of the surgery ops: incise, join, patch, resect, measure, undo, redo.
#include <cmath>

#include "session_ops.hpp"
#include "session_defaults.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::app::detail {

namespace {

std::vector<engine::Vec3> points(Fields& f, const std::string& key) {
  std::vector<engine::Vec3> out;
  for (const auto& p : f.vec3_list(key)) out.push_back(vec(p));
  return out;
}

engine::ChainSpec parse_chain(Fields& c, double max_distance) {
  engine::ChainSpec spec;
  spec.max_distance = max_distance;
  if (c.has("loop")) {
    if (c.has("from") || c.has("to") || c.has("via"))
      c.fail("loop", "give either loop, or from and to (and optionally via)");
    spec.loop = true;
    spec.from = vec(c.required_vec3("loop"));
  } else {
    spec.from = vec(c.required_vec3("from"));
    spec.to = vec(c.required_vec3("to"));
    if (auto v = c.optional_vec3("via")) spec.via = vec(*v);
  }
  c.finish();
  return spec;
}

engine::ShellMaterial parse_material_object(Fields& m, engine::ShellMaterial mat) {
  mat.youngs_modulus = m.optional_positive("youngs_modulus", mat.youngs_modulus);
  mat.poisson_ratio = m.optional_number("poisson_ratio", mat.poisson_ratio);
  if (mat.poisson_ratio < 0.0 || mat.poisson_ratio >= 0.5)
    m.fail("poisson_ratio", "must be in [0, 0.5)");
  mat.thickness = m.optional_positive("thickness", mat.thickness);
  mat.density = m.optional_positive("density", mat.density);
  mat.drilling_factor = m.optional_positive("drilling_factor", mat.drilling_factor);
  m.finish();
  return mat;
}

engine::Vec3 nonzero_normal(Fields& f, const std::string& key) {
  const engine::Vec3 n = vec(f.required_vec3(key));
  if (!(n.norm() > 0.0)) f.fail(key, "must not be the zero vector");
  return n;
}

InciseOp parse_incise(Fields& f) {
  InciseOp op;
  op.object = object_name(f);
  op.points = points(f, "points");
  if (op.points.size() < 2) f.fail("points", "an incision needs at least 2 points");
  op.params = detail::incision_defaults(f.format_version());
  op.params.mode = engine::parse_incision_mode(f.optional_choice("mode", "cut", {"cut", "snap"}));
  // The former sliver guard: still read and checked, so sessions that set it load, but the
  // cut's vertices now lie on the curve (docs/session-format.md).
  if (f.optional_positive("sliver_fraction", 0.2) >= 0.5) f.fail("sliver_fraction", "must be below 0.5");
  op.params.max_distance = f.optional_positive("max_distance", op.params.max_distance);
  op.params.remesh = f.optional_bool("remesh", op.params.remesh);
  op.params.target_edge_length =  // absent: the host's spacing (0)
      f.has("target_edge_length") ? f.optional_positive("target_edge_length", 1.0) : op.params.target_edge_length;
  op.params.band_width = f.optional_positive("band_width", op.params.band_width);
  if (op.params.band_width > 20.0) f.fail("band_width", "must be at most 20 edge lengths");
  op.params.grading = f.optional_number("grading", op.params.grading);
  if (!(op.params.grading >= 1.0 && op.params.grading <= 10.0)) f.fail("grading", "must be in [1, 10]");
  op.params.repair_below_deg = f.optional_number("repair_below_angle", op.params.repair_below_deg);
  if (!(op.params.repair_below_deg >= 0.0 && op.params.repair_below_deg <= 40.0))
    f.fail("repair_below_angle", "must be in [0, 40] degrees");
  if (op.params.mode == engine::IncisionMode::SnapToEdges && f.has("remesh") && op.params.remesh)
    f.fail("remesh", "a snapped incision follows mesh edges and is not remeshed");
  if (op.params.mode == engine::IncisionMode::SnapToEdges) op.params.remesh = false;
  return op;
}

JoinOp parse_join(Fields& f) {
  JoinOp op;
  op.object = object_name(f);
  const double max_distance = f.optional_positive("max_distance", 1.0);
  op.join = detail::join_defaults(f.format_version());
  op.join.placement = engine::parse_suture_placement(
      f.optional_choice("placement", "mean", {"mean", "onto_b"}));
  if (f.has("chains") == f.has("sutures"))
    f.fail("sutures", "give either chains (one suture: two chains) or sutures (a list of "
                      "{\"a\": chain, \"b\": chain})");
  if (f.has("chains")) {
    auto chains = f.object_list("chains");
    if (chains.size() != 2) f.fail("chains", "must hold exactly two chains");
    op.sutures.push_back({parse_chain(chains[0], max_distance), parse_chain(chains[1], max_distance)});
  } else {
    for (auto& s : f.object_list("sutures")) {
      auto a = s.optional_object("a");
      auto b = s.optional_object("b");
      if (!a) s.fail("a", "missing (the first chain)");
      if (!b) s.fail("b", "missing (the second chain)");
      op.sutures.push_back({parse_chain(*a, max_distance), parse_chain(*b, max_distance)});
      s.finish();
    }
  }
  op.remesh = f.optional_bool("remesh", f.format_version() >= 3);
  op.seams = detail::seam_defaults(f.format_version());
  return op;
}

// Default patch: glutaraldehyde-fixed pericardium of an infant repair, roughly 0.4 mm thick
// and stiffer than the native wall (a few MPa at physiological strains).
engine::ShellMaterial default_patch_material() {
  engine::ShellMaterial m;
  m.youngs_modulus = 3.0;
  m.poisson_ratio = 0.45;
  m.thickness = 0.4;
  return m;
}

// Every field of a patch but its object (design_patch gives the object once for its parts).
void parse_patch_fields(Fields& f, PatchOp& op) {
  op.start = vec(f.required_vec3("start"));
  op.end = vec(f.required_vec3("end"));
  op.params = detail::patch_plan_defaults(f.format_version());
  op.seams = detail::seam_defaults(f.format_version());
  op.join = detail::join_defaults(f.format_version());
  op.params.shape = engine::parse_patch_shape(
      f.optional_choice("shape", "ellipse", {"ellipse", "diamond", "triangle"}));
  op.params.width = f.optional_positive("width", op.params.width);
  // A patch narrower than a suture bite is not a patch: laid into the slit it is a sliver the
  // relaxation grinds on for minutes (a 2 um patch, ../shared/robustness/fuzzed_session_hang_a5c86ed71d).
  constexpr double kMinPatchWidth = 0.5;  // mm
  if (op.params.width < kMinPatchWidth) f.fail("width", "must be at least 0.5 mm (a suture bite)");
  op.params.length = f.optional_number("length", 0.0);
  if (op.params.length < 0.0) f.fail("length", "must be >= 0 (0 = the incision's length)");
  op.params.edge_length = f.optional_number("edge_length", 0.0);
  if (op.params.edge_length < 0.0) f.fail("edge_length", "must be >= 0 (0 = the lips' spacing)");
  // Since format 2, the lips' spacing is not taken below a fifth of the width (version 1
  // sessions keep their patches as they were cut).
  if (f.format_version() >= 2) op.params.min_edge_length = op.params.width / 5.0;
  op.params.max_distance = f.optional_positive("max_distance", op.params.max_distance);
  op.material = default_patch_material();
  if (auto m = f.optional_object("material")) op.material = parse_material_object(*m, op.material);
  using SeamRemesh = PatchOp::SeamRemesh;
  const bool remesh = f.optional_bool("remesh", f.format_version() >= 2);
  op.remesh = !remesh                   ? SeamRemesh::None
              : f.format_version() >= 3 ? SeamRemesh::Matched
                                        : SeamRemesh::HostAfterJoin;
}

PatchOp parse_patch(Fields& f) {
  PatchOp op;
  op.object = object_name(f);
  parse_patch_fields(f, op);
  return op;
}

ResectOp parse_resect(Fields& f) {
  ResectOp op;
  op.object = object_name(f);
  for (auto& p : f.object_list("planes")) {
    engine::CutPlane plane;
    plane.origin = vec(p.required_vec3("origin"));
    plane.normal = nonzero_normal(p, "normal");
    p.finish();
    op.planes.push_back(plane);
  }
  if (op.planes.size() > 2) f.fail("planes", "give one plane (divide) or two (resect a band)");
  if (auto s = f.optional_vec3("seed")) op.seed = vec(*s);
  if (op.planes.size() == 1 && !op.seed)
    f.fail("seed", "missing: with one plane, a point in the part to remove is required");
  op.params = detail::resection_defaults(f.format_version());
  op.params.radius = f.optional_positive("radius", op.params.radius);
  op.params.sliver_fraction = f.optional_positive("sliver_fraction", op.params.sliver_fraction);
  if (op.params.sliver_fraction >= 0.5) f.fail("sliver_fraction", "must be below 0.5");
  op.anastomosis = f.optional_bool("anastomosis", false);
  if (op.anastomosis && op.planes.size() != 2)
    f.fail("anastomosis", "needs two planes (two loose ends to suture)");
  if (auto a = f.optional_vec3("align")) op.align = vec(*a);
  op.remesh = f.optional_bool("remesh", f.format_version() >= 3);
  op.seams = detail::seam_defaults(f.format_version());
  op.join = detail::join_defaults(f.format_version());
  return op;
}

// Every field of a measure but its object.
void parse_measure_fields(Fields& f, MeasureOp& op) {
  op.name = f.required_string("name");
  if (f.has("plane") == f.has("centreline"))
    f.fail("plane", "give either plane {origin, normal} or centreline [points] or \"auto\"");
  if (auto p = f.optional_object("plane")) {
    engine::Plane plane;
    plane.origin = vec(p->required_vec3("origin"));
    plane.normal = nonzero_normal(*p, "normal");
    p->finish();
    op.plane = plane;
  } else if (const auto* c = f.raw("centreline"); c->is_string()) {
    if (c->get<std::string>() != "auto") f.fail("centreline", "must be \"auto\" or an array of [x, y, z] points");
    op.auto_centreline = true;
    op.from = vec(f.required_vec3("from"));
    op.to = vec(f.required_vec3("to"));
    if (op.from == op.to) f.fail("to", "must differ from 'from'");
    op.stations = f.optional_int("stations", 0, 1, 10000);
  } else {
    op.centreline = points(f, "centreline");
    if (op.centreline.size() < 2) f.fail("centreline", "needs at least 2 points");
    op.stations = f.optional_int("stations", op.stations, 1, 10000);
  }
  op.max_radius = f.optional_number("max_radius", 0.0);
  if (op.max_radius < 0.0) f.fail("max_radius", "must be >= 0 (0 = unlimited)");
}

MeasureOp parse_measure(Fields& f) {
  MeasureOp op;
  op.object = object_name(f);
  parse_measure_fields(f, op);
  return op;
}

DesignPatchOp parse_design_patch(Fields& f) {
  DesignPatchOp op;
  const std::string object = object_name(f);
  auto part = [&](const char* key, const char* what) {
    std::optional<Fields> p = f.optional_object(key);
    if (!p) f.fail(key, std::string("missing: ") + what);
    return std::move(*p);
  };
  Fields patch = part("patch", "the patch to size ({start, end, shape, material, ...}, no width)");
  if (patch.has("width")) patch.fail("width", "is what design_patch chooses: give width_range");
  op.patch.object = object;
  parse_patch_fields(patch, op.patch);
  patch.finish();
  Fields run = part("simulate", "each candidate's run ({relax: {...}, ...}, as a simulate op)");
  if (!run.has("relax")) run.fail("relax", "missing: each candidate's run relaxes its sutures");
  op.simulate = parse_simulate_op(run);
  run.finish();
  if (op.simulate.objects.empty()) op.simulate.objects = {object};
  Fields measure = part("measure", "the lumen profile that is sized ({name, centreline, ...})");
  op.measure.object = object;
  parse_measure_fields(measure, op.measure);
  if (op.measure.plane) measure.fail("plane", "design_patch measures along a centreline");
  measure.finish();
  const auto range = f.optional_range("width_range");
  if (!range) f.fail("width_range", "missing: [narrowest, widest] patch to try, mm");
  op.width_min = (*range)[0];
  op.width_max = (*range)[1];
  if (op.width_min < 0.5) f.fail("width_range", "must start at 0.5 mm or more (a suture bite)");
  if (op.width_max > 50.0) f.fail("width_range", "must end at 50 mm or less");
  Fields target = part("target", "{min_area_mm2: ...}, {coarctation_index: ...} or {z_score: ..., site: ..., bsa_m2: ...}");
  if (int(target.has("min_area_mm2")) + int(target.has("coarctation_index")) + int(target.has("z_score")) != 1)
    target.fail("min_area_mm2", "give one of min_area_mm2, coarctation_index and z_score");
  if (target.has("min_area_mm2")) {
    op.target = DesignPatchOp::Target::MinArea;
    op.target_value = target.optional_positive("min_area_mm2", 1.0);
  } else if (target.has("z_score")) {
    // The smallest equivalent diameter must reach the z-score's: a MinArea target.
    DesignPatchOp::ZScore z;
    z.z = target.optional_number("z_score", 0.0);
    if (!(z.z >= -5.0 && z.z <= 5.0)) target.fail("z_score", "must be in [-5, 5]");
    z.site = engine::parse_arch_site(
        target.optional_choice("site", "isthmus", {"transverse_arch", "isthmus", "descending_aorta"}));
    if (!target.has("bsa_m2")) target.fail("bsa_m2", "missing: the child's body surface area, m^2");
    z.bsa_m2 = target.optional_number("bsa_m2", 0.0);
    static_assert(engine::kMinBsa == 0.1 && engine::kMaxBsa == 2.0, "the message below names the range");
    if (!(z.bsa_m2 >= engine::kMinBsa && z.bsa_m2 <= engine::kMaxBsa))
      target.fail("bsa_m2", "must be in [0.1, 2] m^2 (the regressions' range)");
    z.diameter_mm = engine::arch_diameter_at_z(z.site, z.bsa_m2, z.z);
    op.target = DesignPatchOp::Target::MinArea;
    op.target_value = 0.25 * M_PI * z.diameter_mm * z.diameter_mm;
    op.z_score = z;
  } else {
    op.target = DesignPatchOp::Target::CoarctationIndex;
    op.target_value = target.optional_positive("coarctation_index", 1.0);
    if (op.target_value > 2.0) target.fail("coarctation_index", "must be in (0, 2]");
  }
  target.finish();
  op.tolerance = f.optional_positive("tolerance", op.tolerance);
  if (op.tolerance > 1.0) f.fail("tolerance", "must be in (0, 1]");
  if (f.has("max_bulge")) {
    op.max_bulge = f.optional_positive("max_bulge", 1.0);
    if (*op.max_bulge < 1.0) f.fail("max_bulge", "must be >= 1 (a ratio of diameters)");
  }
  op.max_relaxations = f.optional_int("max_relaxations", op.max_relaxations, 2, 50);
  if (f.has("plot")) op.plot = output_file(f, "plot", {".png"});
  return op;
}

}  // namespace

DistanceOp parse_distance(Fields& f) {
  DistanceOp op;
  op.name = f.required_string("name");
  op.a = f.required_string("a");
  op.b = f.required_string("b");
  if (f.has("spacing")) op.spacing = f.optional_positive("spacing", 1.0);
  return op;
}

RemeshOp parse_remesh(Fields& f) {
  RemeshOp op;
  op.object = object_name(f);
  if (f.has("near") && f.has("below_angle"))
    f.fail("below_angle", "give either near or below_angle (the region is around one or the other)");
  if (f.has("near")) {
    op.near = points(f, "near");
    if (op.near.empty()) f.fail("near", "give at least one point");
    op.radius = f.optional_positive("radius", 1.0);
    if (!f.has("radius")) f.fail("radius", "missing: the region is the faces within radius mm of near");
  } else if (f.has("below_angle")) {
    op.below_angle = f.optional_number("below_angle", 0.0);
    if (!(op.below_angle > 0.0 && op.below_angle <= 60.0)) f.fail("below_angle", "must be in (0, 60] degrees");
    op.radius = f.optional_positive("radius", 1.0);
    if (!f.has("radius"))
      f.fail("radius", "missing: the region is the faces within radius mm of those with a smaller angle than below_angle");
  } else if (f.has("radius")) {
    f.fail("radius", "goes with near or below_angle (what the region is around)");
  }
  if (f.has("target_edge_length")) op.target_edge_length = f.optional_positive("target_edge_length", 1.0);
  op.grading = f.optional_number("grading", 1.0);
  if (!(op.grading >= 1.0 && op.grading <= 10.0)) f.fail("grading", "must be in [1, 10]");
  if (op.grading > 1.0 && op.near.empty()) f.fail("grading", "needs near (the curve it grows from)");
  op.passes = detail::remesh_passes_defaults(f.format_version());
  op.passes.iterations = f.optional_int("iterations", op.passes.iterations, 1, 100);
  return op;
}

const std::vector<OpParser>& surgery_op_parsers() {
  static const std::vector<OpParser> parsers = {
      {"incise", [](Fields& f, const std::filesystem::path&) -> Op { return parse_incise(f); }},
      {"join", [](Fields& f, const std::filesystem::path&) -> Op { return parse_join(f); }},
      {"patch", [](Fields& f, const std::filesystem::path&) -> Op { return parse_patch(f); }},
      {"resect", [](Fields& f, const std::filesystem::path&) -> Op { return parse_resect(f); }},
      {"remesh", [](Fields& f, const std::filesystem::path&) -> Op { return parse_remesh(f); }},
      {"measure", [](Fields& f, const std::filesystem::path&) -> Op { return parse_measure(f); }},
      {"design_patch", [](Fields& f, const std::filesystem::path&) -> Op { return parse_design_patch(f); }},
      {"distance", [](Fields& f, const std::filesystem::path&) -> Op { return parse_distance(f); }},
      {"undo", [](Fields&, const std::filesystem::path&) -> Op { return UndoOp{}; }},
      {"redo", [](Fields&, const std::filesystem::path&) -> Op { return RedoOp{}; }},
  };
  return parsers;
}

}  // namespace sutura::app::detail
