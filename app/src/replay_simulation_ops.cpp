// Execution of the simulation ops (material, constrain, loads, solve, simulate, probe, check).
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "replay_run.hpp"
#include "sutura/app/report.hpp"
#include "sutura/app/simulation.hpp"
#include "sutura/engine/sim/point_triangle_distance.hpp"
#include "sutura/engine/sim/rigid_modes.hpp"
#include "sutura/engine/sim/selection.hpp"
#include "sutura/engine/sim/stability.hpp"
#include "sutura/engine/sim/unload.hpp"
#include "sutura/engine/measure/vertex_fields.hpp"

namespace sutura::app::detail {

namespace fs = std::filesystem;

namespace {

// The pre-operative state ("before" of measurements and snapshots, the reference of
// displacements and probes) becomes the object at `positions`, its strains those of its
// current state on its current rest.
void make_before(SceneObject& obj, const std::vector<engine::Vec3>& positions) {
  obj.sim.reference = positions;
  // (The mesh now, not as loaded: a remesh may have come between.)
  obj.before = obj.mesh;
  obj.before.set_positions(positions);
  const auto shell = state_model_of(obj);  // the model whose solve made this state
  const engine::ShellProblem problem{&obj.mesh.faces(), &obj.sim.rest, &obj.sim.materials,
                                     &obj.sim.face_material, obj.mesh.num_vertices()};
  obj.before_measures = engine::face_to_vertex(obj.before, shell->measures(problem, obj.sim.state));
}

// A state that is to become "before" must be the vessel before surgery.
void require_unedited(const SceneObject& obj, const std::string& what) {
  // The rest becomes one vertex field (engine/sim/unload.hpp) for unload: a suture's 1:n rest
  // mapping or a relaxation under way would be lost; for either, an edit already made would
  // make "before" a state after surgery.
  if (!obj.sim.marks.incisions.empty() || !obj.sim.marks.sutures.empty() || obj.sim.relax_from)
    throw std::runtime_error("'" + obj.name + "' has been incised or sutured; " + what);
}

// Loads that reached full value become part of the applied (constant) loads.
void commit_pending_loads(SceneObject& o) {
  auto& p = o.sim.pending_loads;
  auto& a = o.sim.applied_loads;
  a.nodal.insert(a.nodal.end(), p.nodal.begin(), p.nodal.end());
  a.pressures.insert(a.pressures.end(), p.pressures.begin(), p.pressures.end());
  a.body_force_per_area += p.body_force_per_area;
  p = engine::Loads{};
  o.sim.pending_factor = 0.0;
}

// An energy minimisation ("minimize") looks for a minimum of strain energy minus the work of
// the loads; a pressure that reaches a rim free to move has no such potential there, and the
// minimisation can stall short of the equilibrium after many steps (measured: the subclavian
// flap's inflation with its LSA end free gave up after 53 s, the residual 3e4 times too large).
// Throws naming the object and a vertex of the rim.
void require_conservative_pressure(MergedSystem& merged) {
  const std::set<std::size_t> rim = free_pressure_rims(merged);
  if (rim.empty()) return;
  const std::size_t node = *rim.begin();
  std::size_t offset = 0;
  for (const auto& [name, x] : merged.positions_by_object(merged.state().x)) {
    if (node < offset + x.size()) {
      const engine::Vec3& p = x[node - offset];
      std::ostringstream m;
      m.precision(3);
      m << std::fixed << "\"minimize\" needs loads with a potential energy, but the pressure on '"
        << name << "' ends at a rim that is free to move (vertex " << node - offset << " at ("
        << p.x() << ", " << p.y() << ", " << p.z() << ")";
      if (rim.size() > 1) m << " and " << rim.size() - 1 << " more";
      m << "): hold the rim (\"fix\") or solve without \"minimize\"";
      throw std::runtime_error(m.str());
    }
    offset += x.size();
  }
}

// What a surgeon must be told about a simulated shape (`what`) beyond the numbers: that it is
// not a stable equilibrium (a small disturbance would carry it off, e.g. buckle a wall that
// came to rest compressed but symmetric), so the measurements describe a shape the vessel
// would not keep; or that it is marginal, or could not be assessed. Empty when stable.
// (Indefinite tangents met on the way are not warned about: they occur at trial iterates of
// ordinary runs, a stretched pair of strips included.) tests/CMakeLists.txt matches these
// sentences to fail a bundled replay.
std::string stability_warning(const engine::Stability& st, const std::string& what) {
  if (st.stable) return {};
  if (!st.assessed) return "the stability of the " + what + " could not be assessed (" + st.summary + ")";
  if (st.negative_modes == 0)
    return "the " + what + " is at the limit of stability (" + st.summary +
           "); a small disturbance may change it, so read its measurements with care";
  return "the " + what + " is not a stable equilibrium (" + st.summary +
         "); the vessel would not keep this shape, so its measurements are not a prediction";
}

// A static equilibrium needs every rigid-body motion of every object restrained: along a free
// one the tangent is singular and the "solution" is whatever round-off picks (an open tube
// under pressure with nothing fixed was reported solved). Throws naming the object and its
// free motions; `what` is the run ("solve"). Contact could hold a body: not checked then.
void require_restrained(const std::vector<SceneObject*>& objs, const std::string& what) {
  for (const SceneObject* o : objs) {
    const auto free = engine::free_rigid_motions(o->sim.state.x, o->sim.constraints);
    if (free.empty()) continue;
    std::string motions;
    for (std::size_t k = 0; k < free.size(); ++k) motions += (k ? "; " : "") + free[k].describe();
    throw std::runtime_error(
        "object '" + o->name + "' can move as a rigid body (" + std::to_string(free.size()) +
        " motion" + (free.size() > 1 ? "s" : "") + " not restrained by any fixed degree of freedom: " +
        motions + "), so a " + what +
        " has no unique equilibrium; fix enough of it (op fix: e.g. \"boundary\": \"all\"), or "
        "use simulate for its dynamics");
  }
}

std::string equilibrium_warning(const engine::RelaxationResult& r) {
  if (!r.stability) return {};
  std::string w = stability_warning(*r.stability, "relaxed shape");
  if (!w.empty() && r.escapes > 0)
    w += " (perturbed along an unstable mode and settled again " + std::to_string(r.escapes) +
         " times without reaching a stable shape)";
  return w;
}

json stability_json(const engine::Stability& st) {
  return {{"assessed", st.assessed},
          {"stable", st.stable},
          {"singular", st.singular},
          {"negative_modes", st.negative_modes},
          {"summary", st.summary}};
}

}  // namespace

std::vector<engine::VertexId> Run::resolve(const SceneObject& obj, const VertexSelection& sel) {
  if (sel.engine) return engine::select_vertices(obj.mesh.positions(), *sel.engine);
  const auto loops = obj.mesh.boundary_loops();
  std::vector<engine::VertexId> ids;
  std::vector<int> wanted;
  if (sel.boundary_loops) wanted = *sel.boundary_loops;
  for (const engine::Vec3& p : sel.boundary_near) {
    int best = -1;
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (const auto v : loops[l])
        if ((obj.mesh.position(v) - p).norm() < d) d = (obj.mesh.position(v) - p).norm(), best = int(l);
    if (best < 0) throw std::runtime_error("object '" + obj.name + "' has no boundary");
    wanted.push_back(best);
  }
  if (!sel.boundary_near.empty() && wanted.empty())
    throw std::runtime_error("object '" + obj.name + "' has no boundary");
  if (wanted.empty())
    for (std::size_t i = 0; i < loops.size(); ++i) wanted.push_back(static_cast<int>(i));
  for (int i : wanted) {
    if (i >= static_cast<int>(loops.size()))
      throw std::runtime_error("object '" + obj.name + "' has " + std::to_string(loops.size()) +
                               " boundary loops; there is no loop " + std::to_string(i));
    ids.insert(ids.end(), loops[i].begin(), loops[i].end());
  }
  if (ids.empty()) throw std::runtime_error("object '" + obj.name + "' has no boundary");
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

std::vector<SceneObject*> Run::objects_named(const std::vector<std::string>& names) {
  std::vector<std::string> which = names;
  if (which.empty())
    for (const auto& o : workspace.objects()) which.push_back(o.name);
  std::vector<SceneObject*> out;
  for (const auto& n : which) out.push_back(&edit(n));
  if (out.empty()) throw std::runtime_error("nothing to simulate: the session has no objects yet");
  return out;
}

json Run::execute(const MaterialOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  auto& materials = obj.sim.materials;
  auto& face_material = obj.sim.face_material;
  const std::size_t faces = obj.mesh.num_faces();
  int index = 0;
  engine::ShellMaterial m;
  if (op.region == MaterialOp::Region::All) {
    m = op.fields.applied_to(engine::ShellMaterial{});
    engine::validate(m);
    materials = {m};
    face_material.assign(faces, 0);
  } else {
    if (op.region == MaterialOp::Region::At) {
      // The face nearest the point, by the exact point-triangle distance (O(faces)).
      double best = std::numeric_limits<double>::infinity();
      std::size_t nearest = 0;
      for (std::size_t f = 0; f < faces; ++f) {
        const auto& t = obj.mesh.faces()[f];
        const double d = engine::closest_point_on_triangle(op.at, obj.mesh.positions()[t[0]],
                                                           obj.mesh.positions()[t[1]],
                                                           obj.mesh.positions()[t[2]])
                             .squared_distance;
        if (d < best) best = d, nearest = f;
      }
      if (!(std::sqrt(best) <= op.max_distance))
        throw std::runtime_error("the point 'at' is " + std::to_string(std::sqrt(best)) +
                                    " mm from the nearest face of '" + op.object + "' (limit " +
                                    std::to_string(op.max_distance) + " mm, max_distance)");
      index = face_material[nearest];
    }
    m = op.fields.applied_to(materials[static_cast<std::size_t>(index)]);
    engine::validate(m);
    materials[static_cast<std::size_t>(index)] = m;
  }
  const auto count = std::count(face_material.begin(), face_material.end(), index);
  json out = {{"object", op.object}, {"material", index}, {"faces", count},
              {"values", {{"youngs_modulus", m.youngs_modulus}, {"poisson_ratio", m.poisson_ratio},
                          {"thickness", m.thickness}}}};
  if (const std::string w = engine::material_warning(m); !w.empty()) out["warning"] = w;
  return out;
}

json Run::execute(const ConstrainOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  const auto ids = resolve(obj, op.where);
  obj.sim.constraints.fix(ids, op.dofs, obj.mesh.num_vertices());
  return {{"object", op.object}, {"vertices", ids.size()}};
}

json Run::execute(const ForceOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  const auto ids = resolve(obj, op.where);
  const double share = op.per_node ? 1.0 : 1.0 / static_cast<double>(ids.size());
  for (auto v : ids)
    obj.sim.pending_loads.nodal.push_back({v.index(), share * op.force, share * op.moment});
  return {{"object", op.object}, {"vertices", ids.size()}};
}

json Run::execute(const LineLoadOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  const auto ids = resolve(obj, op.where);
  const auto chain = boundary_chain(obj, ids);
  const auto loads = engine::lump_line_load(obj.mesh.positions(), chain, op.force_per_length);
  obj.sim.pending_loads.nodal.insert(obj.sim.pending_loads.nodal.end(), loads.begin(), loads.end());
  return {{"object", op.object}, {"vertices", chain.size()}};
}

json Run::execute(const PressureOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  obj.sim.pending_loads.pressures.push_back({{}, op.pressure});
  return {{"object", op.object}};
}

json Run::execute(const BodyForceOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  if (op.per_area) {
    obj.sim.pending_loads.body_force_per_area += *op.per_area;
  } else {
    // rho * t * a on each face's rest area, lumped equally to its corners.
    for (std::size_t e = 0; e < obj.mesh.num_faces(); ++e) {
      const auto& m = obj.sim.materials[obj.sim.face_material[e]];
      const double area = engine::rest_area(obj.sim.rest.elements[e]);
      for (int k = 0; k < 3; ++k)
        obj.sim.pending_loads.nodal.push_back(
            {static_cast<std::size_t>(obj.mesh.faces()[e][k]),
             m.density * m.thickness * area / 3.0 * *op.acceleration, engine::Vec3::Zero()});
    }
  }
  return {{"object", op.object}};
}

json Run::execute(const SolveOp& op) {
  remember();
  const auto objs = objects_named(op.objects);
  double start = 0.0;
  for (SceneObject* o : objs) start = std::max(start, o->sim.pending_factor);
  if (op.load_factor < start)
    throw std::runtime_error("load_factor " + std::to_string(op.load_factor) +
                             " is below the load factor already reached (" +
                             std::to_string(start) + ")");
  if (op.as_before)
    for (const SceneObject* o : objs)
      require_unedited(*o,
                       "a solve with as_before makes the pre-operative vessel, so solve it before "
                       "the first edit");
  require_restrained(objs, "static solve");
  const auto model = make_model(op.model);
  MergedSystem merged(objs, *model, nullptr, op.collapse_barrier ? &op.barrier : nullptr);
  if (op.minimize) require_conservative_pressure(merged);
  engine::StaticSolverParams params = op.params;
  params.keep_going = [this] { return !past_deadline(); };
  params.lambda_start = start;
  params.lambda_end = op.load_factor;
  // One workspace for the solve and the stability check: the tangent's sparsity pattern is
  // built once (about 0.5 s at 20k elements).
  engine::SolverWorkspace workspace;
  const engine::StaticResult r =
      engine::solve_static(merged.system(), merged.state(), params, &workspace);
  merged.write_back();
  json history = json::array();
  for (const auto& h : r.history)
    history.push_back({{"lambda", h.lambda}, {"iteration", h.iteration},
                       {"residual", h.residual}, {"energy", h.energy},
                       {"potential", h.potential}, {"step_length", h.step_length}});
  for (SceneObject* o : objs) {
    if (r.converged && op.load_factor >= 1.0) commit_pending_loads(*o);
    else o->sim.pending_factor = r.lambda_reached;
  }
  if (!r.converged) {
    const std::string advice = solve_advice(r.message, op.minimize, free_pressure_rims(merged).empty());
    throw std::runtime_error(advice.empty() ? r.message : r.message + ". " + advice);
  }
  if (op.as_before)
    for (SceneObject* o : objs) make_before(*o, o->mesh.positions());
  json out = {{"model", model->name()}, {"converged", r.converged}, {"iterations", r.iterations},
              {"residual", r.residual}, {"energy", r.energy}, {"load_factor", r.lambda_reached},
              {"history", history}};
  if (op.as_before) out["as_before"] = true;
  if (op.minimize) out["quasi_newton_iterations"] = r.quasi_newton_iterations;
  if (op.check_stability) {
    engine::StabilityParams sp;
    sp.lambda = r.lambda_reached;
    const engine::Stability st =
        engine::check_stability(merged.system(), merged.state(), sp, &workspace);
    out["equilibrium"] = stability_json(st);
    if (const std::string w = stability_warning(st, "solved shape"); !w.empty()) out["warning"] = w;
  }
  return out;
}

json Run::execute(const UnloadOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  require_unedited(obj,
                   "unload finds the unloaded shape of the vessel as imaged, so unload it before "
                   "the first edit");
  if (obj.sim.applied_loads.empty() && obj.sim.pending_loads.empty())
    throw std::runtime_error("'" + op.object +
                             "' has no loads to unload: set the loads it was imaged under first "
                             "(e.g. op pressure, 0.0107 MPa for 80 mmHg)");
  std::vector<SceneObject*> objs{&obj};
  require_restrained(objs, "unload");
  const auto model = make_model(op.solve.model);
  MergedSystem merged(objs, *model, nullptr, op.solve.collapse_barrier ? &op.solve.barrier : nullptr);
  if (op.solve.minimize) require_conservative_pressure(merged);
  engine::UnloadParams params = op.params;
  params.solver = op.solve.params;
  params.solver.keep_going = [this] { return !past_deadline(); };
  const std::vector<engine::Vec3> imaged = merged.state().x;
  engine::SolverWorkspace workspace;
  const engine::UnloadResult r = engine::unload(merged.system(), imaged, params, &workspace);
  if (r.stopped) throw OpCancelled(r.message);
  if (!r.converged) throw std::runtime_error(r.message);
  // The imaged shape stays the pre-operative one ("before" of measurements, the reference of
  // displacements); the object is now in equilibrium under its loads there.
  merged.state() = r.state;
  merged.velocity().setZero();
  merged.rest() = r.rest;
  merged.write_back();
  obj.sim.rest = r.rest;
  make_before(obj, imaged);
  commit_pending_loads(obj);
  json history = json::array();
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    const engine::UnloadIteration& h = r.history[k];
    json e = {{"iteration", k + 1}, {"solved", h.solved}, {"step", h.step},
              {"accelerated", h.accelerated},
              {"solver_iterations", h.solver_iterations}};
    if (h.solved) {
      e["max_deviation_mm"] = h.max_deviation;
      e["rms_deviation_mm"] = h.rms_deviation;
    }
    history.push_back(e);
  }
  json out = {{"model", model->name()},
              {"converged", true},
              {"iterations", r.history.size()},
              {"solver_iterations", r.solver_iterations},
              {"max_deviation_mm", r.max_deviation},
              {"rms_deviation_mm", r.rms_deviation},
              {"tolerance_mm", r.tolerance},
              {"max_unloading_mm", r.max_unloading},
              {"history", history}};
  if (op.solve.check_stability) {
    const engine::Stability st =
        engine::check_stability(merged.system(), merged.state(), engine::StabilityParams{}, &workspace);
    out["equilibrium"] = stability_json(st);
    if (const std::string w = stability_warning(st, "imaged shape under its loads"); !w.empty())
      out["warning"] = w;
  }
  return out;
}

json Run::execute(const SimulateOp& op) {
  remember();
  if (op.relax) return relax(op);
  const auto objs = objects_named(op.objects);
  const auto model = make_model(op.model);
  MergedSystem merged(objs, *model, op.contact ? &*op.contact : nullptr,
                      op.collapse_barrier ? &op.barrier : nullptr);
  engine::DynamicsState ds{merged.state(), merged.velocity()};
  bool cancelled = false;
  const engine::StepHook hook = [&](int step) {
    cancelled = !report_progress("simulate", step, op.params.steps, merged, ds.shell.x);
    return !cancelled;
  };
  engine::DynamicsParams params = op.params;
  params.keep_going = [this] { return !past_deadline(); };
  const engine::DynamicsResult r = engine::simulate_dynamics(merged.system(), ds, params, hook);
  merged.state() = ds.shell;
  merged.velocity() = ds.velocity;
  merged.write_back();
  if (cancelled || r.stopped)
    throw OpCancelled("cancelled after " + std::to_string(r.steps_done) + " of " +
                      std::to_string(op.params.steps) + " steps");
  if (!r.ok) throw std::runtime_error(r.message);
  for (SceneObject* o : objs) commit_pending_loads(*o);
  return {{"model", model->name()}, {"steps", r.steps_done},
          {"newton_iterations", r.newton_iterations}, {"factorizations", r.factorizations},
          {"step_cuts", r.step_cuts}, {"restarts", r.restarts},
          {"kinetic_energy", r.kinetic_energy},
          {"strain_energy", r.strain_energy}, {"residual", r.residual}};
}

json Run::relax(const SimulateOp& op) {
  const auto objs = objects_named(op.objects);
  double s_start = 0.0;
  bool pending = false;
  for (const SceneObject* o : objs)
    if (o->sim.relax_from) {
      pending = true;
      s_start = std::max(s_start, o->sim.relax_s);
    }
  if (!pending)
    throw std::runtime_error("nothing to relax: no suture since the last relaxation (use "
                             "simulate without relax to settle)");
  engine::RelaxationParams params = *op.relax;
  params.statics.keep_going = [this] { return !past_deadline(); };
  params.dynamics.keep_going = params.statics.keep_going;
  params.s_start = s_start;
  if (params.s_end < s_start)
    throw std::runtime_error("relax.until " + std::to_string(params.s_end) +
                             " is below the relaxation already reached (" +
                             std::to_string(s_start) + ")");
  if (params.solver == engine::RelaxationSolver::Static && !op.contact) require_restrained(objs, "static relaxation");
  const auto model = make_model(op.model);
  MergedSystem merged(objs, *model, op.contact ? &*op.contact : nullptr,
                      op.collapse_barrier ? &op.barrier : nullptr);
  const engine::RestState y0 = merged.relax_from();
  const engine::RestState x0 = merged.rest();
  merged.rest() = engine::rest_at(y0, x0, s_start);
  // A false from report_progress cancels the relaxation (RelaxationResult::cancelled).
  const engine::RelaxationHook hook = [&](const engine::RelaxationProgress& p) {
    return report_progress(p.phase, p.step, p.steps, merged, merged.state().x, p.s, p.residual,
                           params.solver == engine::RelaxationSolver::Static ? p.newton_iterations : -1,
                           p.quasi_newton_iterations, {params.s_start, params.s_end});
  };
  const engine::RelaxationResult r =
      engine::relax(merged.system(), merged.rest(), y0, x0, merged.state(), params, hook);
  merged.velocity().setZero();
  merged.write_back();
  for (SceneObject* o : objs) {
    if (!o->sim.relax_from) continue;
    if (r.s_reached >= 1.0) {
      o->sim.relax_from.reset();
      o->sim.relax_s = 0.0;
    } else {
      o->sim.relax_s = r.s_reached;
    }
  }
  if (r.cancelled) throw OpCancelled("relaxation cancelled at s = " + std::to_string(r.s_reached));
  if (!r.ok) {
    const std::string advice =
        relaxation_advice(r.message, op.collapse_barrier, params.solver, params.s_end);
    throw std::runtime_error(advice.empty() ? r.message : r.message + ". " + advice);
  }
  for (SceneObject* o : objs) commit_pending_loads(*o);
  json history = json::array();
  for (const auto& h : r.history)
    history.push_back({{"s", h.s}, {"phase", h.phase}, {"residual", h.residual}, {"energy", h.energy}});
  json out = {{"model", model->name()},
              {"relaxation", params.solver == engine::RelaxationSolver::Static ? "static" : "dynamic"},
              {"s_reached", r.s_reached},
              {"newton_iterations", r.newton_iterations},
              {"quasi_newton_iterations", r.quasi_newton_iterations},
              {"indefinite_iterations", r.indefinite_iterations},
              {"residual", r.residual},
              {"energy", r.energy},
              {"history", history}};
  if (r.stability) {
    out["equilibrium"] = stability_json(*r.stability);
    out["equilibrium"]["escapes"] = r.escapes;
    if (r.stability_before_escapes) {
      out["equilibrium"]["before_escapes"] = {
          {"negative_modes", r.stability_before_escapes->negative_modes},
          {"summary", r.stability_before_escapes->summary}};
    }
  }
  if (const std::string w = equilibrium_warning(r); !w.empty()) out["warning"] = w;
  return out;
}

bool Run::report_progress(const std::string& phase, int step, int steps,
                          const MergedSystem& merged, const std::vector<engine::Vec3>& x,
                          double s, double residual, int newton_iterations,
                          int quasi_newton_iterations, std::array<double, 2> s_range) {
  if (past_deadline()) return false;
  if (!options.on_progress) return true;
  RunProgress p;
  p.phase = phase;
  p.step = step;
  p.steps = steps;
  p.fraction = steps > 0 ? static_cast<double>(step) / steps : 0.0;
  p.s = s;
  p.s_start = s_range[0];
  p.s_end = s_range[1];
  p.residual = residual;
  p.newton_iterations = newton_iterations;
  p.quasi_newton_iterations = quasi_newton_iterations;
  p.positions = merged.positions_by_object(x);
  return options.on_progress(p);
}

json Run::execute(const ProbeOp& op) {
  const SceneObject& obj = object(op.object);
  // Vertices are found and measured from where their material points were before the
  // operation (carried across incisions and sutures).
  const auto& reference = obj.sim.reference;
  const auto v = engine::select_vertices(reference, engine::SelectNearest{{op.point}})[0];
  const engine::Vec3 u = obj.mesh.position(v) - reference[v.index()];
  const Eigen::AngleAxisd aa(obj.sim.state.D[v.index()]);
  const engine::Vec3 rot = aa.angle() * aa.axis();
  const engine::Vec3& at = reference[v.index()];
  json j = {{"object", op.object},  {"vertex", v.value},
            {"reference", {at.x(), at.y(), at.z()}},
            {"ux", u.x()}, {"uy", u.y()}, {"uz", u.z()}, {"|u|", u.norm()},
            {"rx", rot.x()}, {"ry", rot.y()}, {"rz", rot.z()}};
  probes[op.name] = j;
  return {{"probe", op.name}, {"values", j}};
}

json Run::execute(const CheckOp& op) {
  if (!op.measurement.empty() || !op.object.empty()) {
    const bool measured = !op.measurement.empty();
    std::string what = measured ? "measurement '" : "object '";
    what += measured ? op.measurement : op.object;
    what += "'";
    if (measured && !measurements.contains(op.measurement))
      throw std::runtime_error("no measurement named '" + op.measurement +
                               "' recorded before this check");
    const json summary = measured ? json() : object_summary(object(op.object));
    const json* v = measured ? &measurements[op.measurement] : &summary;
    std::stringstream path(op.quantity);
    for (std::string key; std::getline(path, key, '.');) {
      if (!v->is_object() || !v->contains(key))
        throw std::runtime_error(what + " has no quantity '" + op.quantity + "'");
      v = &(*v)[key];
    }
    if (!v->is_number())
      throw std::runtime_error(what + " quantity '" + op.quantity + "' is not a number");
    const double got = v->get<double>();
    double lo = 0.0, hi = 0.0;
    if (op.range) {
      lo = (*op.range)[0], hi = (*op.range)[1];
    } else {
      const double allowed = std::max(op.abs_tol, op.rel_tol * std::abs(op.value));
      lo = op.value - allowed, hi = op.value + allowed;
    }
    const bool pass = got >= lo && got <= hi;
    json j = {{measured ? "measurement" : "object", measured ? op.measurement : op.object},
              {"quantity", op.quantity}, {"value", got}, {"min", lo}, {"max", hi}, {"pass", pass}};
    checks.push_back(j);
    if (!pass) {
      std::ostringstream m;
      m << "check failed: " << what << " " << op.quantity << " = " << got
        << ", expected in [" << lo << ", " << hi << "]";
      throw std::runtime_error(m.str());
    }
    return j;
  }
  if (!probes.contains(op.probe))
    throw std::runtime_error("no probe named '" + op.probe + "' recorded before this check");
  const double got = probes[op.probe][op.quantity].get<double>();
  const double allowed = std::max(op.abs_tol, op.rel_tol * std::abs(op.value));
  const bool pass = std::abs(got - op.value) <= allowed;
  json j = {{"probe", op.probe}, {"quantity", op.quantity}, {"value", got},
            {"expected", op.value}, {"allowed_error", allowed},
            {"relative_error", op.value != 0.0 ? std::abs(got - op.value) / std::abs(op.value) : 0.0},
            {"pass", pass}};
  checks.push_back(j);
  if (!pass) {
    std::ostringstream m;
    m << "check failed: probe '" << op.probe << "' " << op.quantity << " = " << got
      << ", expected " << op.value << " +- " << allowed;
    throw std::runtime_error(m.str());
  }
  return j;
}

// Orders boundary vertices `ids` along their boundary loop; they must be one contiguous run.
std::vector<engine::VertexId> Run::boundary_chain(const SceneObject& obj,
                                                  const std::vector<engine::VertexId>& ids) {
  const std::set<engine::VertexId> want(ids.begin(), ids.end());
  for (const auto& loop : obj.mesh.boundary_loops()) {
    if (std::none_of(loop.begin(), loop.end(), [&](auto v) { return want.count(v) > 0; }))
      continue;
    // Start right after a vertex that is not selected, so the run does not wrap around.
    const std::size_t n = loop.size();
    std::size_t start = 0;
    while (start < n && want.count(loop[start]) > 0) ++start;
    if (start == n) {  // the whole loop: close it by repeating the first vertex
      if (ids.size() != n)
        throw std::runtime_error("the selected vertices do not all lie on one boundary loop");
      std::vector<engine::VertexId> closed = loop;
      closed.push_back(loop.front());
      return closed;
    }
    std::vector<engine::VertexId> chain;
    for (std::size_t i = 1; i <= n; ++i) {
      const auto v = loop[(start + i) % n];
      if (want.count(v) > 0) {
        if (!chain.empty() && want.count(loop[(start + i + n - 1) % n]) == 0)
          throw std::runtime_error("the selected boundary vertices are not one contiguous run");
        chain.push_back(v);
      }
    }
    if (chain.size() != ids.size())
      throw std::runtime_error("the selected vertices do not all lie on one boundary loop");
    return chain;
  }
  throw std::runtime_error("a line load needs vertices on the boundary");
}

}  // namespace sutura::app::detail
