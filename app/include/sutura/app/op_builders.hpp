#pragma once
// The session ops the GUI emits, as JSON lines in the format of docs/session-format.md.
// Pure functions: what a click means is decided here, in one testable place.
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sutura/app/element_check.hpp"
#include "sutura/app/plan.hpp"
#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/resect.hpp"
#include "sutura/render/camera.hpp"

namespace sutura::app {

nlohmann::json point_json(const engine::Vec3& p);
/// The value of a float field as the shortest decimal that reads back as that float (0.45f
/// gives 0.45, not 0.449999988079071), so that a recording says what the surgeon typed.
double as_typed(float value);

/// {"op": "generate", "object", "shape", ...extra}; extra holds shape parameters.
nlohmann::json generate_op(const std::string& object, const std::string& shape,
                           const nlohmann::json& extra = nlohmann::json::object());
/// How the session file `session` names `file`: relative to the session's directory when the
/// file lies inside it (a session's relative paths are read from its own directory, so a
/// session and the meshes beside it can move together), otherwise absolute. A file that does
/// not exist, or that the relative path would not reach (symbolic links), is named absolute.
std::filesystem::path path_from(const std::filesystem::path& file, const std::filesystem::path& session);
/// {"op": "load", "object", "file"}, the file named by path_from(file, recording). With
/// `prepare`, the file is a segmentation export prepared as it loads ({"prepare":
/// {"smoothing": 10[, "edge_length"]}}, edge_length only when > 0).
/// `landmarks` (not empty): the landmarks file naming the mesh's ends, named like `file`.
nlohmann::json load_op(const std::string& object, const std::filesystem::path& file,
                       const std::filesystem::path& recording, bool prepare = false,
                       double prepare_edge_length = 0.0, const std::filesystem::path& landmarks = {});
/// The material of one region of `object` (MaterialOp): region 0, the wall, as {"region":
/// "wall"}; a patch's (region > 0) as {"at": p}, p the centroid of the region's lowest-numbered
/// face now. Only the values given are recorded: the region keeps the others, and the other
/// regions keep their materials. Throws std::invalid_argument for a region no face has.
nlohmann::json material_op(const engine::SurfaceMesh& mesh, const std::vector<int>& face_material,
                           const std::string& object, int region, std::optional<double> youngs_modulus,
                           std::optional<double> poisson_ratio, std::optional<double> thickness);
/// The same for a region of `obj` (its mesh, materials by face and name).
nlohmann::json material_op(const SceneObject& obj, int region, std::optional<double> youngs_modulus,
                           std::optional<double> poisson_ratio, std::optional<double> thickness);
/// The wall material the bundled arch sessions give the bundled neonatal aorta (E 1 MPa,
/// nu 0.45, 0.6 mm; assets/sessions/*.jsonl), as the `material` op of `object`'s wall, with a
/// note saying so: what the window records after loading the bundled aortic arch. (The
/// engine's default material, which a loaded mesh otherwise has, is 1 mm thick.)
nlohmann::json bundled_arch_wall_op(const std::string& object);
/// Fixes every DOF of boundary loop `loop`: the `fix` op when the build has it, else the
/// equivalent `constrain` op with a boundary selection.
nlohmann::json fix_loop_op(const std::string& object, int loop, bool have_fix_op);
/// Fixes every DOF of every open end: {"op": "fix", "boundary": "all"}.
nlohmann::json fix_all_ends_op(const std::string& object);
/// Fixes every DOF of the given vertices (a boundary run picked in the view), likewise.
nlohmann::json fix_vertices_op(const std::string& object, const std::vector<int>& vertices,
                               bool have_fix_op);
/// Fixes every DOF of the boundary run from `from` to `to` (two clicks in the view; the run
/// the join op would resolve between them: nearest boundary vertices, boundary direction), as
/// fix_vertices_op. Throws engine::InvalidArgument when no run joins them.
nlohmann::json fix_run_op(const engine::SurfaceMesh& mesh, const std::string& object, const engine::Vec3& from,
                          const engine::Vec3& to, bool have_fix_op);
nlohmann::json incise_op(const std::string& object, const std::vector<engine::Vec3>& points,
                         bool snap);
/// One side of a suture as the join op resolves it: the arc from `from` to `to` in the
/// boundary direction. Ends at the same point without `via`: the whole loop there. With `via`
/// (a point on the arc): the arc through it, which is how the two lips' copies of one point
/// of a cut name the arc from one lip round to the other (a flap's rim, an aortotomy).
struct ChainEnds {
  engine::Vec3 from, to;
  std::optional<engine::Vec3> via;
  [[nodiscard]] bool loop() const { return from == to && !via; }
};
/// `onto_b`: placement "onto_b" (side a drawn onto side b); otherwise the default (mean). A
/// loop chain is recorded as {"loop": p}, the others as {"from", "to"[, "via"]}.
nlohmann::json join_op(const std::string& object, const ChainEnds& a, const ChainEnds& b,
                       bool onto_b = false);
nlohmann::json patch_op(const std::string& object, const std::string& shape,
                        const engine::Vec3& lip_start, const engine::Vec3& lip_end, double width,
                        const nlohmann::json& material);
/// {"op": "resect"} with the planes, `radius` (mm) and `anastomosis`; the seed is the op's
/// default (between the two planes' origins).
nlohmann::json resect_op(const std::string& object, const std::vector<engine::CutPlane>& planes, double radius,
                         bool anastomosis);
/// Remesh of the faces within `radius` of the polyline through `near` (the whole object when
/// empty) to `target_edge_length` (0: the region's mean), graded by `grading` (> 1, with
/// `near` only) away from it.
nlohmann::json remesh_op(const std::string& object, const std::vector<engine::Vec3>& near,
                         double radius, double target_edge_length, double grading, int iterations);
/// Remesh of the faces within `radius` mm, along the edges, of a face with an angle below
/// `below_angle` degrees (RemeshOp::below_angle), to `target_edge_length` (0: their mean).
nlohmann::json remesh_small_angles_op(const std::string& object, double below_angle, double radius,
                                      double target_edge_length, int iterations);
/// What keeps the triangles of a run's result at `below_angle` degrees or more (the window's
/// "Keep triangles well shaped" after a simulation): for each object of `angles` whose smallest
/// angle is below it, remesh_small_angles_op(object, below_angle, radius, 0, 3); then one
/// static solve of those objects back to equilibrium ("check_stability"; "collapse_barrier"
/// when `collapse_barrier`), as an energy minimisation when `minimize` (loads_have_potential:
/// its steps only go downhill, where full Newton steps from a remeshed, slightly unbalanced
/// shape can run off), else by Newton. Empty when none is below.
std::vector<nlohmann::json> keep_angle_ops(const std::vector<SmallestAngle>& angles, double below_angle,
                                           double radius, bool minimize, bool collapse_barrier);
/// keep_angle_ops for the shapes of `workspace` (smallest_angles), as the window runs them
/// after a run: `below_angle` in degrees, `radius` in mm along the edges; only objects that
/// are restrained (restrained(): a settle of a free-floating one has no unique equilibrium, so
/// it is left as it is), settled in one solve, an energy minimisation when the loads of all of
/// them have a potential (loads_have_potential), else Newton. Empty when no such object is
/// below the limit. Throws as loads_have_potential and MergedSystem do (moments on a 3-DOF
/// model). Cost O(F log F).
std::vector<nlohmann::json> keep_angle_plan(const Workspace& workspace, double below_angle, double radius,
                                            bool collapse_barrier);
/// The static equilibrium under every load (the window's Simulate with nothing to relax, *Static
/// equilibrium*): {"op": "solve", "load_steps": 4, "check_stability": true}, with "minimize"
/// when `minimize` (loads_have_potential) and "collapse_barrier" when `collapse_barrier`.
nlohmann::json static_solve_op(bool minimize, bool collapse_barrier);
/// Implicit dynamics; `relax_steps` > 0 adds {"relax": {"steps": N}} (rest-shape relaxation),
/// otherwise the scheme is recorded ("linearized").
nlohmann::json simulate_op(int steps, double dt, int relax_steps, bool collapse_barrier = false);
/// The flap relaxation, as the bundled subclavian flap session runs it: a static relaxation
/// to s = 0.6, then damped dynamics (pace-setting density 1e-6 t/mm^3, dt 0.5 ms, 80 steps
/// to s = 1 and 40 more) and a static settle. Two simulate ops, to run one after the other.
std::vector<nlohmann::json> flap_relaxation_ops(bool collapse_barrier);
/// A diameter z-score as a patch design's target (DesignPatchOp::ZScore): the smallest lumen
/// area must reach that of a circle whose diameter has z-score `z` at `site` (one of
/// z_score_sites()) for the child's body surface area `bsa_m2`.
struct DesignZScore {
  double z = -1.0;
  std::string site = "isthmus";
  double bsa_m2 = 0.2;
};
/// The sites with a z-score regression, by their session names ("transverse_arch", ...).
std::vector<std::string> z_score_sites();
/// The diameter (mm) that `target` asks for (Pettersen et al. 2008, docs/anatomy.md). Throws
/// std::runtime_error, in words, for a site not in z_score_sites(), z outside [-5, 5] or a
/// body surface area outside [0.1, 2] m^2. O(1).
double z_score_diameter_mm(const DesignZScore& target);
/// What the window's patch design asks for (DesignPatchOp): the smallest lumen area along
/// `centreline` (a polyline, mm; sections no wider than `max_radius` mm, one per mm of it plus
/// one, from 11 to 101) at least `min_area_mm2`, or with `z_score` that z-score's area,
/// within `tolerance` (a fraction), the largest diameter along it at most `max_bulge` times the
/// diameter at its end, for widths in [width_min, width_max] mm.
struct DesignTarget {
  double min_area_mm2 = 20.0;
  std::optional<DesignZScore> z_score;
  double tolerance = 0.05;
  double width_min = 2.0, width_max = 8.0;
  double max_bulge = 1.4;
  std::vector<engine::Vec3> centreline;
  double max_radius = 0.0;
};
/// {"op": "design_patch"} of the patch `patch` (a patch_op; its width is what is chosen),
/// each candidate relaxed in `relax_steps` increments (with the collapse barrier when asked)
/// and measured as `target` says, under the name "design_lumen".
nlohmann::json design_patch_op(const nlohmann::json& patch, int relax_steps, bool collapse_barrier,
                               const DesignTarget& target);
/// Cross-section of `object` by a plane, reported under `name`.
/// {"op": "measure", "centreline": "auto", "from", "to"}: the lumen profile along the automatic
/// centreline between the points nearest `from` and `to` (e.g. two open ends' centres).
nlohmann::json lumen_profile_op(const std::string& object, const std::string& name, const engine::Vec3& from,
                                const engine::Vec3& to);
nlohmann::json measure_op(const std::string& object, const std::string& name,
                          const engine::Vec3& origin, const engine::Vec3& normal);
/// The window's view as a snapshot: its camera (eye, target, up, vertical field of view), its
/// size (each half's, side by side) and, with a field, its colour range.
struct SnapshotView {
  render::Camera camera;
  int width = 1280, height = 960;
  std::optional<std::array<float, 2>> range;
  std::optional<render::ClipPlane> clip;  ///< the Cut open plane, recorded as the op's `clip`
};
nlohmann::json snapshot_op(const std::string& file, const SnapshotView& view, bool side_by_side,
                           const std::string& field);
nlohmann::json export_op(const std::string& object, const std::string& file);
/// The cutting template of the patch sewn into `object` last (`patches`: how many patches the
/// object has, patch_template.hpp's patch_materials): that patch's number, and as `proximal`
/// the `start` of the last applied `patch` op (or `design_patch` op's `patch`) on the object
/// in `plan`. Throws
/// std::invalid_argument with the reason, in words for the window, when the object has no
/// patch or the plan holds no applied patch op on it.
nlohmann::json patch_template_op(const Plan& plan, const std::string& object, std::size_t patches,
                                 const std::string& file);
/// The plan report (plan_report.hpp) as `file` (.html) and the PDF beside it (same name,
/// .pdf).
nlohmann::json plan_report_op(const std::string& file);

}  // namespace sutura::app
