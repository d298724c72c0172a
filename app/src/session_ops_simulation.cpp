// Parsers of the simulation ops: material, constrain, force, line_load, pressure, body_force,
// solve, simulate, probe, check.
#include "session_ops.hpp"
#include "session_defaults.hpp"
#include "sutura/engine/sim/linear_solver.hpp"

namespace sutura::app::detail {

namespace {

// Exactly one of: vertices, nearest, box, plane, boundary.
VertexSelection parse_selection(Fields& f) {
  const std::vector<std::string> keys = {"vertices", "nearest", "box", "plane", "boundary",
                                         "boundary_near"};
  int count = 0;
  for (const auto& k : keys) count += f.has(k) ? 1 : 0;
  if (count != 1)
    f.fail("", "give exactly one vertex selection: vertices, nearest, box, plane, boundary or "
               "boundary_near");
  VertexSelection sel;
  if (f.has("boundary_near")) {
    for (const auto& p : f.vec3_list("boundary_near")) sel.boundary_near.push_back(vec(p));
    return sel;
  }
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
  if (f.has("at")) {
    if (f.has("region")) f.fail("at", "give either region or at, not both");
    op.region = MaterialOp::Region::At;
    op.at = vec(f.required_vec3("at"));
    op.max_distance = f.optional_positive("max_distance", op.max_distance);
  } else {
    op.region = f.optional_choice("region", "all", {"all", "wall"}) == "wall" ? MaterialOp::Region::Wall
                                                                             : MaterialOp::Region::All;
  }
  auto& m = op.fields;
  const auto positive = [&](const char* key, std::optional<double>& out) {
    if (f.has(key)) out = f.optional_positive(key, 1.0);
  };
  positive("youngs_modulus", m.youngs_modulus);
  if (f.has("poisson_ratio")) {
    m.poisson_ratio = f.optional_number("poisson_ratio", 0.0);
    if (*m.poisson_ratio < 0.0 || *m.poisson_ratio >= 0.5) f.fail("poisson_ratio", "must be in [0, 0.5)");
  }
  positive("thickness", m.thickness);
  positive("density", m.density);
  positive("drilling_factor", m.drilling_factor);
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

// `fix`: a constraint on all six DOFs unless `dofs` says otherwise (holding vessel ends).
ConstrainOp parse_fix(Fields& f) { return parse_constrain(f); }

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

// The settings of a static solve: every field of `solve` but `objects` and `load_factor`.
void parse_solver_settings(Fields& f, SolveOp& op) {
  op.model = f.optional_choice("model", op.model, {"corotational", "discrete"});
  op.collapse_barrier = f.optional_bool("collapse_barrier", op.collapse_barrier);
  auto& p = op.params;
  p.load_steps = f.optional_int("load_steps", p.load_steps, 1, 100000);
  p.tolerance = f.optional_positive("tolerance", p.tolerance);
  if (p.tolerance >= 1.0) f.fail("tolerance", "must be below 1");
  p.max_iterations = f.optional_int("max_iterations", p.max_iterations, 1, 10000);
  p.line_search = f.optional_bool("line_search", p.line_search);
  p.linear_solver = linear_solver(f, p.linear_solver);
  p.linear = f.optional_choice("analysis", "nonlinear", {"nonlinear", "linear"}) == "linear";
  op.check_stability = f.optional_bool("check_stability", op.check_stability);
  if (op.check_stability && p.linear)
    f.fail("check_stability", "needs the nonlinear analysis (a linear one has no equilibrium state to test)");
  op.minimize = f.optional_bool("minimize", op.minimize);
  if (op.minimize && p.linear)
    f.fail("minimize", "needs the nonlinear analysis (a linear one solves once, it minimises nothing)");
  p.shift_indefinite = op.minimize;
  p.quasi_newton_steps = f.optional_int("quasi_newton_steps", p.quasi_newton_steps, 0, 1000);
  if (!op.minimize && f.has("quasi_newton_steps"))
    f.fail("quasi_newton_steps", "applies only with \"minimize\": true (Newton steps otherwise)");
}

SolveOp parse_solve(Fields& f) {
  SolveOp op;
  op.params = static_solver_defaults(f.format_version());
  op.barrier = area_barrier_defaults(f.format_version());
  op.objects = f.optional_string_list("objects");
  op.load_factor = f.optional_positive("load_factor", op.load_factor);
  if (op.load_factor > 1.0) f.fail("load_factor", "must be in (0, 1]");
  parse_solver_settings(f, op);
  op.as_before = f.optional_bool("as_before", op.as_before);
  if (op.as_before && op.load_factor < 1.0)
    f.fail("as_before", "needs load_factor 1 (\"before\" is the vessel under its full loads)");
  return op;
}

UnloadOp parse_unload(Fields& f) {
  UnloadOp op;
  op.solve.params = static_solver_defaults(f.format_version());
  op.solve.barrier = area_barrier_defaults(f.format_version());
  op.params = unload_defaults(f.format_version());
  op.object = object_name(f);
  parse_solver_settings(f, op.solve);
  if (op.solve.params.linear)
    f.fail("analysis", "unload needs the nonlinear analysis (a linear one has no loaded shape to match)");
  op.params.max_iterations = f.optional_int("iterations", op.params.max_iterations, 1, 1000);
  op.params.tolerance = f.optional_number("shape_tolerance", op.params.tolerance);
  if (!(op.params.tolerance >= 0.0)) f.fail("shape_tolerance", "must be >= 0 (mm; 0 = 1 % of the mean edge length)");
  return op;
}

SimulateOp parse_simulate(Fields& f) {
  SimulateOp op;
  op.params = dynamics_defaults(f.format_version());
  op.barrier = area_barrier_defaults(f.format_version());
  op.objects = f.optional_string_list("objects");
  op.model = f.optional_choice("model", op.model, {"corotational", "discrete"});
  op.collapse_barrier = f.optional_bool("collapse_barrier", op.collapse_barrier);
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
  p.max_step_cuts = f.optional_int("max_step_cuts", p.max_step_cuts, 0, 10);
  p.corotated_damping = f.optional_bool("corotated_damping", p.corotated_damping);
  // The relaxation always uses Newton (relaxation.cpp); asked for linearized, it is an error.
  const bool relax = f.has("relax");
  p.scheme = f.optional_choice("scheme", relax ? "newton" : "linearized",
                               {"newton", "linearized"}) == "linearized"
                 ? engine::DynamicsScheme::Linearized
                 : engine::DynamicsScheme::Newton;
  if (p.scheme == engine::DynamicsScheme::Linearized && relax)
    f.fail("scheme", "the relaxation changes the rest shape every step: it uses newton");
  p.linear_solver = linear_solver(f, p.linear_solver);
  if (auto r = f.optional_object("relax")) {
    engine::RelaxationParams rp = relaxation_defaults(f.format_version());
    rp.solver = engine::parse_relaxation_solver(
        r->optional_choice("solver", "static", {"static", "dynamic"}));
    rp.steps = r->optional_int("steps", rp.steps, 1, 1000000);
    rp.s_end = r->optional_number("until", 1.0);
    if (!(rp.s_end > 0.0 && rp.s_end <= 1.0)) r->fail("until", "must be in (0, 1]");
    if (r->has("density")) {
      if (rp.solver != engine::RelaxationSolver::Dynamic)
        r->fail("density", "only the dynamic relaxation has a density (it sets its pace)");
      rp.density = r->optional_positive("density", 1.0);
    }
    rp.settle = r->optional_bool("settle", rp.settle);
    if (!rp.settle && r->has("settle_steps"))
      r->fail("settle_steps", "has no effect with \"settle\": false (no settling at all)");
    rp.settle_steps = r->optional_int("settle_steps", rp.settle_steps, 0, 1000000);
    rp.statics.tolerance = r->optional_positive("tolerance", rp.statics.tolerance);
    if (rp.statics.tolerance >= 1.0) r->fail("tolerance", "must be below 1");
    rp.statics.max_iterations =
        r->optional_int("max_iterations", rp.statics.max_iterations, 1, 1000);
    rp.check_stability = r->optional_bool("check_stability", rp.check_stability);
    rp.max_escapes = r->optional_int("max_escapes", rp.max_escapes, 0, 100);
    rp.statics.quasi_newton_steps =
        r->optional_int("quasi_newton_steps", rp.statics.quasi_newton_steps, 0, 1000);
    rp.statics.linear_solver = p.linear_solver;
    rp.dynamics = p;
    r->finish();
    op.relax = rp;
  }
  if (auto c = f.optional_object("contact")) {
    engine::ContactParams cp = contact_defaults(f.format_version());
    cp.distance = c->optional_positive("distance", cp.distance);
    cp.stiffness = c->optional_positive("stiffness", cp.stiffness);
    c->finish();
    op.contact = cp;
  }
  return op;
}

ProbeOp parse_probe(Fields& f) {
  ProbeOp op;
  op.object = object_name(f);
  op.name = f.required_string("name");
  op.point = vec(f.required_vec3("point"));
  return op;
}

// `value` with `rel_tol` and/or `abs_tol` (both >= 0, not both 0).
void value_with_tolerances(Fields& f, CheckOp& op) {
  op.value = f.optional_number("value", 0.0);
  op.rel_tol = f.optional_number("rel_tol", 0.0);
  op.abs_tol = f.optional_number("abs_tol", 0.0);
  if (op.rel_tol < 0.0) f.fail("rel_tol", "must be >= 0");
  if (op.abs_tol < 0.0) f.fail("abs_tol", "must be >= 0");
  if (op.rel_tol == 0.0 && op.abs_tol == 0.0) f.fail("rel_tol", "give rel_tol and/or abs_tol");
}

CheckOp parse_check(Fields& f) {
  CheckOp op;
  const int kinds = int(f.has("probe")) + int(f.has("measurement")) + int(f.has("object"));
  if (kinds > 1)
    f.fail(f.has("measurement") ? "measurement" : "object",
           "give one of probe, measurement or object");
  if (f.has("measurement") || f.has("object")) {
    if (f.has("measurement"))
      op.measurement = f.required_string("measurement");
    else
      op.object = f.required_string("object");
    op.quantity = f.required_string("quantity");
    op.range = f.optional_range("range");
    if (op.range) {
      if (f.has("value")) f.fail("value", "give either range or value with tolerances");
      return op;
    }
    if (!f.has("value")) f.fail("value", "missing (or give range: [min, max])");
    value_with_tolerances(f, op);
    return op;
  }
  op.probe = f.required_string("probe");
  op.quantity = f.optional_choice("quantity", "", {"ux", "uy", "uz", "rx", "ry", "rz", "|u|"});
  if (op.quantity.empty()) f.fail("quantity", "missing (ux, uy, uz, rx, ry, rz or |u|)");
  if (!f.has("value")) f.fail("value", "missing");
  value_with_tolerances(f, op);
  return op;
}

}  // namespace

SimulateOp parse_simulate_op(Fields& f) { return parse_simulate(f); }

const std::vector<OpParser>& simulation_op_parsers() {
  static const std::vector<OpParser> parsers = {
      {"material", [](Fields& f, const std::filesystem::path&) -> Op { return parse_material(f); }},
      {"constrain", [](Fields& f, const std::filesystem::path&) -> Op { return parse_constrain(f); }},
      {"fix", [](Fields& f, const std::filesystem::path&) -> Op { return parse_fix(f); }},
      {"force", [](Fields& f, const std::filesystem::path&) -> Op { return parse_force(f); }},
      {"line_load", [](Fields& f, const std::filesystem::path&) -> Op { return parse_line_load(f); }},
      {"pressure", [](Fields& f, const std::filesystem::path&) -> Op { return parse_pressure(f); }},
      {"body_force", [](Fields& f, const std::filesystem::path&) -> Op { return parse_body_force(f); }},
      {"solve", [](Fields& f, const std::filesystem::path&) -> Op { return parse_solve(f); }},
      {"unload", [](Fields& f, const std::filesystem::path&) -> Op { return parse_unload(f); }},
      {"simulate", [](Fields& f, const std::filesystem::path&) -> Op { return parse_simulate(f); }},
      {"probe", [](Fields& f, const std::filesystem::path&) -> Op { return parse_probe(f); }},
      {"check", [](Fields& f, const std::filesystem::path&) -> Op { return parse_check(f); }},
  };
  return parsers;
}

}  // namespace sutura::app::detail
