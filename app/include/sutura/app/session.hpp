#pragma once
// Planning sessions: a JSON Lines file, one action per line, after a versioned header line.
// The format is documented in docs/session-format.md; this header is its parser.
//
// Every field is checked while parsing, before anything runs, so a typo on line 40 is
// reported before a minute of simulation is spent on lines 1-39. Unknown fields are errors
// too (a misspelt optional field would otherwise be silently ignored).
#include <array>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "sutura/engine/generators.hpp"
#include "sutura/engine/shell/material.hpp"
#include "sutura/engine/sim/area_barrier.hpp"
#include "sutura/engine/sim/constraints.hpp"
#include "sutura/engine/sim/dynamics.hpp"
#include "sutura/engine/sim/selection.hpp"
#include "sutura/engine/sim/static_solver.hpp"
#include "sutura/engine/sim/unload.hpp"
#include "sutura/engine/measure/cross_section.hpp"
#include "sutura/engine/measure/z_score.hpp"
#include "sutura/engine/patient/prepare.hpp"
#include "sutura/engine/sim/contact.hpp"
#include "sutura/engine/surgery/boundary_chain.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/join.hpp"
#include "sutura/engine/surgery/patch_plan.hpp"
#include "sutura/engine/surgery/relaxation.hpp"
#include "sutura/engine/surgery/remesh.hpp"
#include "sutura/engine/surgery/resect.hpp"
#include "sutura/engine/surgery/seam_match.hpp"

namespace sutura::app {

/// The newest session format version this build reads and writes. A session keeps its meaning
/// across versions: a default that changes is keyed by the version of the session's header
/// (docs/session-format.md lists them). 2: `incise` remeshes the band around a cut-through
/// incision unless "remesh": false. 3: `join`, `patch` and `resect` match their seams (both
/// chains resampled to one spacing and remeshed around before the suture) and `resect`
/// remeshes the band around its cut, unless "remesh": false. 4: a cut-through `incise` whose
/// band keeps an angle below 20 degrees remeshes it again, finer at the cut
/// ("repair_below_angle"). 5: the faces just outside that band which its remesh splits are
/// the band's, and the repair tries two finer remeshes more.
inline constexpr int kSessionFormatVersion = 5;

/// A session that cannot be read or run. `what()` reads "FILE:LINE: op 'OP': field 'F': problem"
/// with the parts that are known.
class SessionError : public std::runtime_error {
 public:
  SessionError(std::string file, int line, std::string op, std::string field,
               const std::string& problem);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }  ///< 1-based; 0 when not tied to a line
  [[nodiscard]] const std::string& op() const { return op_; }
  [[nodiscard]] const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_;
  std::string op_;
  std::string field_;
};

/// A point or direction as a session line gives it (mm), in double precision.
using Vec3d = std::array<double, 3>;

// --- ops ----------------------------------------------------------------------------------

/// Creates an object from a procedural generator.
struct GenerateOp {
  std::string object;
  std::variant<engine::TubeParams, engine::StripParams, engine::PatchParams,
               engine::CylinderPanelParams>
      params;
  Vec3d translate = {0, 0, 0};  ///< mm, applied after generation
  /// Add the generated mesh to the existing object `object` as a separate part (e.g. the
  /// second of two strips to be sutured), made of that object's first material.
  bool append = false;
};

/// A load's `prepare`: the file is a segmentation export, made a vessel to plan on as it is
/// loaded (engine::prepare_vessel: caps opened as ends, smoothed, remeshed; what `sutura
/// prepare` does with the same settings). Every setting is the session format version's
/// (detail::prepare_defaults), not the engine's own defaults, but for `edge_length` (mm; none:
/// 16 edges around the narrowest end) and `smoothing_iterations` (0 to 100), which the op
/// gives; the replay sets the face limit.
struct PrepareSpec {
  engine::PrepareParams params;
};

/// Loads an object from a mesh file (path relative to the session file).
struct LoadOp {
  std::string object;
  std::filesystem::path file;  ///< resolved against the session file's directory
  double weld_tolerance = 1e-6;
  std::optional<PrepareSpec> prepare;
  /// A landmarks file (`sutura generate`'s landmarks.json): the open ends listed under the
  /// mesh file's stem name the object's ends (SceneObject::ends). Resolved like `file`.
  std::optional<std::filesystem::path> landmarks;
};

/// Camera of a snapshot: explicit eye/target/up, or a view direction fitted to the objects.
struct CameraSpec {
  std::optional<Vec3d> eye;     ///< with target: explicit camera
  std::optional<Vec3d> target;
  Vec3d up = {0, 0, 1};
  Vec3d view = {-0.4, 1.0, -0.35};  ///< direction from the eye towards the scene when fitted
  double fov_deg = 35.0;
};

/// A plane that cuts a snapshot open to show the lumen (render::ClipPlane): what lies on the side
/// `normal` points to is not drawn, in both halves of a side-by-side.
struct ClipSpec {
  Vec3d point{};
  Vec3d normal{};  ///< unit length (the parser normalises it)
};

/// Per-vertex field shown as colours.
enum class Field { None, Displacement, X, Y, Z, MembraneStrain, Bending, EnergyDensity };

/// Renders the named objects (all when empty) to a PNG inside the output directory.
struct SnapshotOp {
  std::filesystem::path file;  ///< relative to the output directory
  int width = 1600;
  int height = 900;  ///< pixels of each view
  std::vector<std::string> objects;
  Field field = Field::None;
  std::optional<std::array<double, 2>> range;  ///< colour-map range; default: data min/max
  CameraSpec camera;
  bool side_by_side = false;  ///< before | after, each width x height
  bool wireframe = false;
  bool boundaries = true;     ///< draw boundary loops as polylines
  bool marks = true;         ///< draw incisions (red) and sutures (green) on the current state
  bool compare_rest = false; ///< side by side: the current rest shape instead of the before-state
  std::optional<ClipSpec> clip;
};

/// Writes an object's current mesh (.obj/.ply/.stl) inside the output directory.
struct ExportOp {
  std::string object;
  std::filesystem::path file;
};

/// Writes the cutting template of a sewn-in patch (.svg or .pdf, at true scale) inside the
/// output directory (patch_template.hpp).
struct ExportPatchTemplateOp {
  std::string object;
  std::filesystem::path file;
  int patch = 1;  ///< 1-based, in the order the patches were sewn in
  engine::Vec3 proximal = engine::Vec3::Zero();  ///< near the patch's proximal end, mm
  double bite_spacing = 1.0;    ///< mm, (0, 20]
  double seam_allowance = 2.0;  ///< mm, [0, 20]
};

/// Writes the report so far (JSON) inside the output directory.
struct ReportOp {
  std::filesystem::path file;
};

/// Writes the plan report (plan_report.hpp) inside the output directory: an HTML file and a
/// PDF of the same content.
struct PlanReportOp {
  std::filesystem::path file;  ///< .html
  std::filesystem::path pdf;   ///< .pdf; the parser's default: `file` with the extension .pdf
  int view_width = 640, view_height = 520;  ///< pixels of each half of a standard view
};

/// The material fields a session line gives; the others come from `base` (applied_to).
struct MaterialFields {
  std::optional<double> youngs_modulus, poisson_ratio, thickness, density, drilling_factor;
  [[nodiscard]] engine::ShellMaterial applied_to(engine::ShellMaterial base) const;
};

/// Sets the material of an object's faces, all of them or one region's.
struct MaterialOp {
  std::string object;
  /// Which faces get the material. All: every face, one material for the whole object (the
  /// fields not given take engine::ShellMaterial's defaults). Wall: the faces of the object's
  /// first material (the vessel wall; patches keep theirs). At: every face of the material of
  /// the face nearest `at` (within `max_distance` mm; a patch, or the wall). With Wall and At,
  /// the fields not given keep that material's values.
  enum class Region { All, Wall, At };
  Region region = Region::All;
  engine::Vec3 at = engine::Vec3::Zero();
  double max_distance = 1.0;
  MaterialFields fields;
};

/// Which vertices an op acts on: one of the engine selections, or boundary loops
/// (`boundary`: loop indices in SurfaceMesh::boundary_loops() order; empty = all loops).
struct VertexSelection {
  std::optional<engine::Selection> engine;
  std::optional<std::vector<int>> boundary_loops;
  /// The boundary loops nearest these points (each the loop with the closest vertex); robust
  /// where loop indices move as incisions open and sutures close loops.
  std::vector<engine::Vec3> boundary_near;
};

/// Fixes degrees of freedom of the selected vertices (zero increment from then on).
struct ConstrainOp {
  std::string object;
  VertexSelection where;
  engine::DofMask dofs = engine::kAllDofs;
};

/// Nodal force and/or moment on the selected vertices: `total` is split equally between
/// them, `per_node` applies it to each.
struct ForceOp {
  std::string object;
  VertexSelection where;
  engine::Vec3 force = engine::Vec3::Zero();   ///< N
  engine::Vec3 moment = engine::Vec3::Zero();  ///< N*mm
  bool per_node = false;
};

/// Force per length (N/mm) along the selected boundary vertices, which must form one
/// contiguous run of a boundary loop.
struct LineLoadOp {
  std::string object;
  VertexSelection where;
  engine::Vec3 force_per_length = engine::Vec3::Zero();
};

/// Follower pressure (MPa) on every face of an object, along the face normals.
struct PressureOp {
  std::string object;
  double pressure = 0.0;
};

/// Body force per rest area (N/mm^2), or an acceleration (mm/s^2) times density * thickness.
struct BodyForceOp {
  std::string object;
  std::optional<engine::Vec3> per_area;
  std::optional<engine::Vec3> acceleration;
};

/// Static equilibrium of the named objects (all when empty) under their loads.
struct SolveOp {
  std::vector<std::string> objects;
  std::string model = "corotational";
  double load_factor = 1.0;  ///< fraction of the pending loads to reach, (0, 1]
  /// Every field as the session's format version defines it where the line leaves it out
  /// (session_defaults.hpp): the parser starts from there, never from the engine's defaults.
  engine::StaticSolverParams params;
  bool collapse_barrier = false;  ///< add engine::AreaBarrier with `barrier` to the system
  engine::AreaBarrierParams barrier;
  /// After a converged nonlinear solve, test whether the state is a stable equilibrium
  /// (engine::check_stability; reported, never changed).
  bool check_stability = false;
  /// Find the equilibrium as a minimum of the total potential energy (params.shift_indefinite:
  /// Levenberg-Marquardt and quasi-Newton steps, line search on the potential). Only for
  /// conservative loads and a stable equilibrium; it cannot follow an unstable branch.
  bool minimize = false;
  /// After the solve, the solved shape is the pre-operative one: "before" of measurements and
  /// snapshots, and the reference of displacements and probes (the vessel pressurised before
  /// the surgery, so that before and after compare like with like). Needs load_factor 1 and
  /// objects not yet incised or sutured.
  bool as_before = false;
};

/// Unloaded (zero-pressure) reference of an imaged vessel (engine::unload): the rest shape
/// whose equilibrium under the object's loads (applied and pending, all at full value) is its
/// current shape. The solver settings are a solve's (`objects`, `load_factor` and the linear
/// analysis excepted); `iterations` bounds the forward solves, `shape_tolerance` (mm, 0 = 1 %
/// of the mean edge length) is how close the loaded shape must come.
struct UnloadOp {
  std::string object;
  SolveOp solve;
  /// The fixed-point iteration: max_iterations (`iterations`), tolerance (`shape_tolerance`) and
  /// the pinned rest, from the format version's defaults (session_defaults.hpp); `solver` is
  /// filled from `solve` by the replay.
  engine::UnloadParams params;
};

/// Implicit dynamics of the named objects (all when empty).
struct SimulateOp {
  std::vector<std::string> objects;
  std::string model = "corotational";
  engine::DynamicsParams params;  ///< as SolveOp::params: the format version's defaults
  /// Rest-shape relaxation of the sutures made since the last run (paper, Sec. 2.3) instead
  /// of plain dynamics; its dynamics settings come from `params`.
  std::optional<engine::RelaxationParams> relax;
  /// Penalty contact between the simulated objects (none when absent).
  std::optional<engine::ContactParams> contact;
  bool collapse_barrier = false;  ///< add engine::AreaBarrier with `barrier` to the system
  engine::AreaBarrierParams barrier;
};

/// Records displacement and rotation of the vertex nearest to `point` (both measured from
/// the vertices' pre-operative positions, carried across edits) in the report under `name`.
struct ProbeOp {
  std::string object;
  std::string name;
  engine::Vec3 point = engine::Vec3::Zero();
};

/// Verification: fails the replay when a probed quantity is outside value ± tolerance.
/// Or, with `measurement`, a quantity of a recorded measurement ("after.min_area_mm2",
/// "area_change_percent", ...), or with `object`, a quantity of the object as report.json
/// lists it ("quality.min_angle_deg", "rest_quality.min_angle_deg", "faces", ...), against
/// value ± tolerance or a [min, max] range.
struct CheckOp {
  std::string probe;
  std::string measurement;
  std::string object;
  std::string quantity;  ///< probe: ux uy uz rx ry rz, or "|u|"; otherwise a dotted path
  double value = 0.0;
  double rel_tol = 0.0;  ///< relative to |value|
  double abs_tol = 0.0;
  std::optional<std::array<double, 2>> range;  ///< measurement and object checks: inclusive bounds
};

// --- surgery ops (session_ops_surgery.cpp; executed by replay_surgery_ops.cpp) -------------

/// Cuts the object along the curve through `points` (engine::incise).
struct InciseOp {
  std::string object;
  std::vector<engine::Vec3> points;
  engine::IncisionParams params;
};

/// One suture: two boundary chains named by points (engine::ChainSpec).
struct SutureSpec {
  engine::ChainSpec a, b;
};

/// Sutures boundary chains of one object (engine::join), several at once. The next
/// `simulate` with `relax` pulls the rest shape from the joined shape to the original.
struct JoinOp {
  std::string object;
  std::vector<SutureSpec> sutures;
  /// The session format version's (detail::join_defaults) with `placement` ("mean" or
  /// "onto_b", where the joined shape starts) from the op; held vertices (any fixed
  /// translation) and the pairing are set by the replay.
  engine::JoinParams join;
  /// Match the seams before joining (engine::match_seams; format 3; before: false).
  bool remesh = true;
  /// That match: the version's (detail::seam_defaults); the replay adds the object's
  /// constraints.
  engine::ResampleChainsParams seams;
};

/// Cuts a patch for the incision between `start` and `end`, lays it over the incision and
/// sutures it to both lips, as part of the same object with its own material.
struct PatchOp {
  std::string object;
  engine::Vec3 start = engine::Vec3::Zero();
  engine::Vec3 end = engine::Vec3::Zero();
  engine::PatchPlanParams params;
  engine::ShellMaterial material;
  /// How the seams are remeshed, by the session's format version when "remesh" is true.
  enum class SeamRemesh {
    None,           ///< "remesh": false, or format 1
    HostAfterJoin,  ///< format 2: the host's side of the seams, after the join
    Matched,        ///< format 3: lips and patch edges resampled to one count, before the join
  };
  SeamRemesh remesh = SeamRemesh::Matched;
  /// The lips' resampling (Matched) and the join, by the session's format version
  /// (detail::seam_defaults, detail::join_defaults).
  engine::ResampleChainsParams seams;
  engine::JoinParams join;
};

/// Removes the region between cut planes (or beyond one) and optionally sutures the two
/// loops left by two planes end to end (anastomosis).
struct ResectOp {
  std::string object;
  std::vector<engine::CutPlane> planes;
  std::optional<engine::Vec3> seed;  ///< a point in the part to remove; default: between the planes
  engine::ResectionParams params;
  bool anastomosis = false;          ///< two planes only
  /// Anastomosis: the loops' first vertices are the ones nearest this point (default: the
  /// point of each loop farthest along +z), so the two ends are sutured without a twist.
  std::optional<engine::Vec3> align;
  /// Remesh the band around the cut, and match the anastomosis's loops (format 3; before:
  /// false).
  bool remesh = true;
  /// The loops' match (and seams.band_passes the band's remesh) and the anastomosis's join,
  /// by the session's format version (detail::seam_defaults, detail::join_defaults).
  engine::ResampleChainsParams seams;
  engine::JoinParams join;
};

/// Remeshes a region of an object (engine::remesh): its sutures, material borders, open
/// boundaries and lips kept as polylines, vertices with a fixed DOF or a point load kept in
/// place; state and rest shape carried across (docs/remeshing.md).
struct RemeshOp {
  std::string object;
  /// The region: faces with a corner within `radius` mm of this polyline (one point: of the
  /// point); empty = the whole object.
  std::vector<engine::Vec3> near;
  /// Or (> 0, degrees) the faces with a corner within `radius` mm, along the edges, of a face
  /// whose smallest angle in the current shape is below this (engine::faces_near_small_angles);
  /// none below: the op leaves the object as it is.
  double below_angle = 0.0;
  double radius = 0.0;
  double target_edge_length = 0.0;  ///< mm; 0 = the region's mean edge length
  double grading = 1.0;             ///< >= 1: finest at `near`, growing by this per band
  /// `iterations` from the op, the other passes by the session's format version.
  engine::RemeshPasses passes;
};

/// Cross-section of an object by a plane, before and after, recorded under `name`.
struct MeasureOp {
  std::string object;
  std::string name;
  std::optional<engine::Plane> plane;
  /// Or a lumen profile: `stations` planes perpendicular to this polyline; reports the
  /// minimum lumen area before and after.
  std::vector<engine::Vec3> centreline;
  /// Or along the automatic centreline (engine::extract_centreline of each shape, its open
  /// boundaries being the ends) between the points nearest `from` and `to`.
  bool auto_centreline = false;
  engine::Vec3 from = engine::Vec3::Zero(), to = engine::Vec3::Zero();
  /// Sections along the centreline; 0 (only with the automatic one): one per mean edge length
  /// of the shape, at least 20.
  int stations = 20;
  double max_radius = 0.0;  ///< mm; 0 = unlimited
};

/// Sizes a patch to a target (docs/patch-design.md): for candidate widths in [width_min,
/// width_max] it sews `patch` in, runs `simulate` and measures `measure`, each from the
/// workspace as the op found it, and leaves the chosen candidate in the workspace as one
/// undoable step, exactly as the three ops with the chosen width would.
struct DesignPatchOp {
  PatchOp patch;        ///< its width is what is chosen; min_edge_length > 0: width / 5
  SimulateOp simulate;  ///< with `relax`
  MeasureOp measure;    ///< a lumen profile along a centreline, on the patch's object
  double width_min = 2.0, width_max = 8.0;  ///< mm, 0.5 <= min < max <= 50
  enum class Target {
    MinArea,           ///< the smallest lumen area along the centreline, mm^2
    CoarctationIndex,  ///< the narrowest equivalent diameter / the distal end's
  };
  Target target = Target::MinArea;
  double target_value = 0.0;
  /// A MinArea target given as a z-score of the site's diameter for the child's body surface
  /// area (engine::arch_diameter_at_z): target_value is the area of a circle of that diameter.
  struct ZScore {
    engine::ArchSite site = engine::ArchSite::Isthmus;
    double bsa_m2 = 0.0;
    double z = 0.0;
    double diameter_mm = 0.0;
  };
  std::optional<ZScore> z_score;
  double tolerance = 0.05;  ///< a width is chosen when the quantity is in [T, T (1 + tolerance)]
  /// Limit: the largest equivalent diameter along the centreline / the distal end's.
  std::optional<double> max_bulge;
  int max_relaxations = 8;  ///< candidates evaluated, 2 ... 50
  /// A PNG plot of the quantity and the bulge against the width, in the output directory
  /// (empty: none).
  std::filesystem::path plot;
};

/// Hausdorff distance between two objects' current shapes (engine::hausdorff_distance),
/// recorded under `name` for `check` (a_to_b_mm, b_to_a_mm, symmetric_mm, ...).
struct DistanceOp {
  std::string name;
  std::string a, b;      ///< object names
  double spacing = 0.0;  ///< mm between samples; 0 = half the smaller mean edge length
};

/// Undo / redo of the last workspace change (edits, constraints, runs).
struct UndoOp {};
struct RedoOp {};

using Op = std::variant<GenerateOp, LoadOp, SnapshotOp, ExportOp, ExportPatchTemplateOp, ReportOp, PlanReportOp, MaterialOp,
                        ConstrainOp, ForceOp, LineLoadOp, PressureOp, BodyForceOp, SolveOp,
                        UnloadOp, SimulateOp, ProbeOp, CheckOp, InciseOp, JoinOp, PatchOp, ResectOp,
                        RemeshOp, MeasureOp, DesignPatchOp, DistanceOp, UndoOp, RedoOp>;

/// One parsed action with where it came from.
struct Action {
  int line = 0;     ///< 1-based line in the session file
  std::string name; ///< the op name as written ("generate", ...)
  Op op;
  /// The line as written (decoded JSON, "note" included): what plan lists and reports
  /// describe (app/plan_text.hpp). Never read by execution.
  nlohmann::json source;
};

struct Session {
  std::filesystem::path file;  ///< the session file (for messages and relative inputs)
  int version = kSessionFormatVersion;
  std::string description;
  std::vector<Action> actions;
};

/// Largest session file read, bytes (64 MiB: the bundled sessions are under 20 kB, a GUI hour
/// records a few hundred kB). The whole text is held in memory while it is parsed.
inline constexpr std::size_t kMaxSessionBytes = std::size_t(64) << 20;

/// Reads and checks a session file: a regular file (a FIFO or device is refused before it is
/// opened) of at most kMaxSessionBytes. Throws SessionError naming file, line and field.
Session load_session(const std::filesystem::path& file);

/// Parses session text; `file` is used for messages and to resolve relative input paths.
Session parse_session(const std::string& text, const std::filesystem::path& file);

/// Parses and checks one action line (already decoded JSON) as if it were line `line` of
/// `file`: the GUI records each action with it before running it. `version`: the format version
/// of the session the line belongs to (it decides defaults that changed). Throws SessionError.
Action parse_action(const nlohmann::json& line_json, const std::filesystem::path& file, int line,
                    int version = kSessionFormatVersion);

/// Names of every op this build understands (for messages and docs tests).
const std::vector<std::string>& known_ops();

}  // namespace sutura::app
