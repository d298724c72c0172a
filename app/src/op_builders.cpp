#include "sutura/app/op_builders.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <cstdlib>
#include <stdexcept>

#include "sutura/app/simulation.hpp"
#include "sutura/engine/measure/z_score.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"

namespace sutura::app {

using nlohmann::json;

double as_typed(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text - 1, value).ptr;
  *end = '\0';
  return std::strtod(text, nullptr);
}

json point_json(const engine::Vec3& p) { return json::array({p.x(), p.y(), p.z()}); }

json generate_op(const std::string& object, const std::string& shape, const json& extra) {
  json op = {{"op", "generate"}, {"object", object}, {"shape", shape}};
  for (const auto& [k, v] : extra.items()) op[k] = v;
  return op;
}

std::filesystem::path path_from(const std::filesystem::path& file, const std::filesystem::path& session) {
  namespace fs = std::filesystem;
  const fs::path absolute = fs::absolute(file).lexically_normal();
  const fs::path dir = fs::absolute(session).parent_path().lexically_normal();
  const fs::path relative = absolute.lexically_relative(dir);
  std::error_code ec;
  if (relative.empty() || *relative.begin() == ".." || !fs::equivalent(dir / relative, absolute, ec))
    return absolute;
  return relative;
}

json load_op(const std::string& object, const std::filesystem::path& file,
             const std::filesystem::path& recording, bool prepare, double prepare_edge_length,
             const std::filesystem::path& landmarks) {
  json op = {{"op", "load"}, {"object", object}, {"file", path_from(file, recording).string()}};
  if (prepare) {
    op["prepare"] = {{"smoothing", 10}};
    if (prepare_edge_length > 0.0) op["prepare"]["edge_length"] = prepare_edge_length;
  }
  if (!landmarks.empty()) op["landmarks"] = path_from(landmarks, recording).string();
  return op;
}

json material_op(const engine::SurfaceMesh& mesh, const std::vector<int>& face_material,
                 const std::string& object, int region, std::optional<double> youngs_modulus,
                 std::optional<double> poisson_ratio, std::optional<double> thickness) {
  json op = {{"op", "material"}, {"object", object}};
  if (youngs_modulus) op["youngs_modulus"] = *youngs_modulus;
  if (poisson_ratio) op["poisson_ratio"] = *poisson_ratio;
  if (thickness) op["thickness"] = *thickness;
  if (region == 0) {
    op["region"] = "wall";
    return op;
  }
  for (std::size_t f = 0; f < face_material.size() && f < mesh.num_faces(); ++f)
    if (face_material[f] == region) {
      const auto& t = mesh.faces()[f];
      op["at"] = point_json((mesh.positions()[t[0]] + mesh.positions()[t[1]] + mesh.positions()[t[2]]) / 3.0);
      return op;
    }
  throw std::invalid_argument("no face has material " + std::to_string(region));
}

json material_op(const SceneObject& obj, int region, std::optional<double> youngs_modulus,
                 std::optional<double> poisson_ratio, std::optional<double> thickness) {
  return material_op(obj.mesh, obj.sim.face_material, obj.name, region, youngs_modulus, poisson_ratio, thickness);
}

json bundled_arch_wall_op(const std::string& object) {
  return {{"op", "material"}, {"object", object}, {"region", "wall"}, {"youngs_modulus", 1.0},
          {"poisson_ratio", 0.45}, {"thickness", 0.6},
          {"note", "the bundled arch sessions' neonatal aortic wall"}};
}

json fix_loop_op(const std::string& object, int loop, bool have_fix_op) {
  return {{"op", have_fix_op ? "fix" : "constrain"}, {"object", object},
          {"boundary", json::array({loop})}, {"dofs", json::array({"all"})}};
}

json fix_all_ends_op(const std::string& object) {
  return {{"op", "fix"}, {"object", object}, {"boundary", "all"}, {"dofs", json::array({"all"})}};
}

json fix_vertices_op(const std::string& object, const std::vector<int>& vertices, bool have_fix_op) {
  return {{"op", have_fix_op ? "fix" : "constrain"}, {"object", object}, {"vertices", vertices},
          {"dofs", json::array({"all"})}};
}

json fix_run_op(const engine::SurfaceMesh& mesh, const std::string& object, const engine::Vec3& from,
                const engine::Vec3& to, bool have_fix_op) {
  engine::ChainSpec spec;
  spec.from = from;
  spec.to = to;
  std::vector<int> ids;
  for (auto v : engine::find_boundary_chain(mesh, spec).vertices) ids.push_back(v.value);
  return fix_vertices_op(object, ids, have_fix_op);
}

json incise_op(const std::string& object, const std::vector<engine::Vec3>& points, bool snap) {
  json pts = json::array();
  for (const auto& p : points) pts.push_back(point_json(p));
  return {{"op", "incise"}, {"object", object}, {"points", pts}, {"mode", snap ? "snap" : "cut"},
          // Recorded, so a session the GUI continues replays the same whatever its version.
          {"remesh", !snap}};
}

json join_op(const std::string& object, const ChainEnds& a, const ChainEnds& b, bool onto_b) {
  json chains = json::array();
  for (const auto* c : {&a, &b}) {
    if (c->loop()) {
      chains.push_back({{"loop", point_json(c->from)}});
      continue;
    }
    json chain = {{"from", point_json(c->from)}, {"to", point_json(c->to)}};
    if (c->via) chain["via"] = point_json(*c->via);
    chains.push_back(chain);
  }
  // Recorded, as for incise: matched seams whatever the version of a session continued.
  json op = {{"op", "join"}, {"object", object}, {"chains", chains}, {"remesh", true}};
  if (onto_b) op["placement"] = "onto_b";
  return op;
}

json patch_op(const std::string& object, const std::string& shape, const engine::Vec3& lip_start,
              const engine::Vec3& lip_end, double width, const json& material) {
  return {{"op", "patch"}, {"object", object}, {"shape", shape}, {"start", point_json(lip_start)},
          {"end", point_json(lip_end)}, {"width", width}, {"material", material},
          {"remesh", true}};
}

json resect_op(const std::string& object, const std::vector<engine::CutPlane>& planes, double radius,
               bool anastomosis) {
  json ps = json::array();
  for (const auto& p : planes) ps.push_back({{"origin", point_json(p.origin)}, {"normal", point_json(p.normal)}});
  // Recorded, as for incise: the same meaning whatever the version of a session continued.
  return {{"op", "resect"}, {"object", object}, {"planes", ps}, {"radius", radius},
          {"anastomosis", anastomosis}, {"remesh", true}};
}

json remesh_small_angles_op(const std::string& object, double below_angle, double radius,
                            double target_edge_length, int iterations) {
  json op = {{"op", "remesh"}, {"object", object}, {"below_angle", below_angle}, {"radius", radius},
             {"iterations", iterations}};
  if (target_edge_length > 0.0) op["target_edge_length"] = target_edge_length;
  return op;
}

std::vector<json> keep_angle_ops(const std::vector<SmallestAngle>& angles, double below_angle, double radius,
                                 bool minimize, bool collapse_barrier) {
  std::vector<json> ops;
  json objects = json::array();
  for (const SmallestAngle& a : angles) {
    if (!(a.degrees < below_angle)) continue;
    ops.push_back(remesh_small_angles_op(a.object, below_angle, radius, 0.0, 3));
    objects.push_back(a.object);
  }
  if (ops.empty()) return ops;
  json solve = {{"op", "solve"}, {"objects", objects}, {"check_stability", true}};
  if (minimize) solve["minimize"] = true;
  if (collapse_barrier) solve["collapse_barrier"] = true;
  ops.push_back(solve);
  return ops;
}

std::vector<json> keep_angle_plan(const Workspace& workspace, double below_angle, double radius,
                                  bool collapse_barrier) {
  std::vector<SmallestAngle> held;
  std::vector<std::string> below;
  for (const SmallestAngle& a : smallest_angles(workspace)) {
    const SceneObject* o = workspace.find(a.object);
    if (o == nullptr || !restrained(*o)) continue;
    held.push_back(a);
    if (a.degrees < below_angle) below.push_back(a.object);
  }
  if (below.empty()) return {};
  return keep_angle_ops(held, below_angle, radius, loads_have_potential(workspace, below), collapse_barrier);
}

json static_solve_op(bool minimize, bool collapse_barrier) {
  json op = {{"op", "solve"}, {"load_steps", 4}, {"check_stability", true}};
  if (minimize) op["minimize"] = true;
  if (collapse_barrier) op["collapse_barrier"] = true;
  return op;
}

json remesh_op(const std::string& object, const std::vector<engine::Vec3>& near, double radius,
              double target_edge_length, double grading, int iterations) {
  json op = {{"op", "remesh"}, {"object", object}, {"iterations", iterations}};
  if (target_edge_length > 0.0) op["target_edge_length"] = target_edge_length;
  if (!near.empty()) {
    json pts = json::array();
    for (const auto& p : near) pts.push_back(point_json(p));
    op["near"] = pts;
    op["radius"] = radius;
    if (grading > 1.0) op["grading"] = grading;
  }
  return op;
}

json simulate_op(int steps, double dt, int relax_steps, bool collapse_barrier) {
  json op = {{"op", "simulate"}, {"steps", steps}, {"dt", dt}};
  // The scheme is recorded, so the session replays the same way should the default change.
  if (relax_steps > 0)
    op["relax"] = {{"steps", relax_steps}};
  else
    op["scheme"] = "linearized";
  if (collapse_barrier) op["collapse_barrier"] = true;
  return op;
}

std::vector<json> flap_relaxation_ops(bool collapse_barrier) {
  // Static while it converges easily; then dynamics, whose inertia carries the gathered flap
  // through its buckling (a static increment there fails); per-step tolerance 1e-4, the
  // transient only leading to the settle (session notes in assets/sessions/subclavian_flap.jsonl).
  json still = {{"op", "simulate"}, {"relax", {{"steps", 16}, {"until", 0.6}}}};
  json moving = {{"op", "simulate"},
                 {"relax",
                  {{"solver", "dynamic"}, {"steps", 80}, {"settle", true}, {"settle_steps", 40},
                   {"max_iterations", 200}, {"density", 1e-6}}},
                 {"dt", 5e-4},
                 {"tolerance", 1e-4},
                 {"mass_damping", 200.0}};
  if (collapse_barrier) still["collapse_barrier"] = moving["collapse_barrier"] = true;
  return {still, moving};
}

json lumen_profile_op(const std::string& object, const std::string& name, const engine::Vec3& from,
                      const engine::Vec3& to) {
  return {{"op", "measure"}, {"object", object}, {"name", name}, {"centreline", "auto"},
          {"from", point_json(from)}, {"to", point_json(to)}};
}

std::vector<std::string> z_score_sites() {
  std::vector<std::string> names;
  for (const engine::ArchSite site :
       {engine::ArchSite::TransverseArch, engine::ArchSite::Isthmus, engine::ArchSite::DescendingAorta})
    names.emplace_back(engine::arch_site_name(site));
  return names;
}

double z_score_diameter_mm(const DesignZScore& target) {
  return engine::arch_diameter_at_z(engine::parse_arch_site(target.site), target.bsa_m2, target.z);
}

json design_patch_op(const json& patch, int relax_steps, bool collapse_barrier, const DesignTarget& target) {
  json part = patch;
  const std::string object = part.value("object", std::string());
  for (const char* key : {"op", "object", "width"}) part.erase(key);
  json relax = {{"steps", relax_steps}};
  json run = {{"objects", json::array({object})}, {"relax", relax}};
  if (collapse_barrier) run["collapse_barrier"] = true;
  json line = json::array();
  double length = 0.0;
  for (std::size_t k = 0; k < target.centreline.size(); ++k) {
    line.push_back(point_json(target.centreline[k]));
    if (k > 0) length += (target.centreline[k] - target.centreline[k - 1]).norm();
  }
  json measure = {{"name", "design_lumen"},
                  {"centreline", line},
                  {"stations", std::clamp(static_cast<int>(std::lround(length)) + 1, 11, 101)}};
  if (target.max_radius > 0.0) measure["max_radius"] = target.max_radius;
  return {{"op", "design_patch"},
          {"object", object},
          {"patch", part},
          {"simulate", run},
          {"measure", measure},
          {"width_range", {target.width_min, target.width_max}},
          {"target", target.z_score ? json{{"z_score", target.z_score->z},
                                           {"site", target.z_score->site},
                                           {"bsa_m2", target.z_score->bsa_m2}}
                                     : json{{"min_area_mm2", target.min_area_mm2}}},
          {"tolerance", target.tolerance},
          {"max_bulge", target.max_bulge}};
}

json measure_op(const std::string& object, const std::string& name, const engine::Vec3& origin,
                const engine::Vec3& normal) {
  return {{"op", "measure"}, {"object", object}, {"name", name},
          {"plane", {{"origin", point_json(origin)}, {"normal", point_json(normal)}}}};
}

json snapshot_op(const std::string& file, const SnapshotView& view, bool side_by_side, const std::string& field) {
  const auto p = [](const render::Point3& v) { return json::array({v[0], v[1], v[2]}); };
  json op = {{"op", "snapshot"},
             {"file", file},
             {"width", view.width},
             {"height", view.height},
             {"side_by_side", side_by_side},
             {"field", field},
             {"camera",
              {{"eye", p(view.camera.eye)},
               {"target", p(view.camera.target)},
               {"up", p(view.camera.up)},
               {"fov_deg", view.camera.fov_y_deg}}}};
  if (view.range && field != "none") op["range"] = {(*view.range)[0], (*view.range)[1]};
  if (view.clip) op["clip"] = {{"point", p(view.clip->point)}, {"normal", p(view.clip->normal)}};
  return op;
}

json export_op(const std::string& object, const std::string& file) {
  return {{"op", "export"}, {"object", object}, {"file", file}};
}

json patch_template_op(const Plan& plan, const std::string& object, std::size_t patches,
                       const std::string& file) {
  if (patches == 0) throw std::invalid_argument("'" + object + "' has no patch: add one with the Patch tool.");
  for (std::size_t i = std::min(plan.applied, plan.steps.size()); i-- > 0;) {
    const json& a = plan.steps[i].source;
    if (a.value("object", std::string()) != object) continue;
    // A patch op, or a design_patch op whose part `patch` sewed the chosen one in.
    const json* patch = plan.steps[i].op == "patch"          ? &a
                        : plan.steps[i].op == "design_patch" && a.contains("patch") ? &a["patch"]
                                                                                   : nullptr;
    if (patch != nullptr && patch->is_object() && patch->contains("start"))
      return {{"op", "export_patch_template"},
              {"object", object},
              {"file", file},
              {"patch", patches},
              {"proximal", (*patch)["start"]}};
  }
  throw std::invalid_argument("No patch step on '" + object +
                              "' in this plan, so the patch's proximal end is not known.");
}

json plan_report_op(const std::string& file) { return {{"op", "plan_report"}, {"file", file}}; }

}  // namespace sutura::app
