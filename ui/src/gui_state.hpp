#pragma once
// The state the GUI's panels and viewport share for one window: the session controller
// (recording + execution), the stage machine, the camera, the planning drafts, the view
// options and the message line. Panels are free functions over it (panels.hpp).
#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sutura/app/element_check.hpp"
#include "sutura/app/resect_preview.hpp"
#include "sutura/app/op_builders.hpp"
#include "scene_picker.hpp"
#include "sutura/app/patch_preview.hpp"
#include "sutura/app/section.hpp"
#include "sutura/ui/orbit_camera.hpp"
#include "sutura/ui/session_controller.hpp"
#include "sutura/ui/stage.hpp"
#include "view_scene.hpp"
#include "widgets.hpp"

namespace sutura::ui {

/// What a left click in the 3-D view does (Plan stage tools; Navigate only orbits).
enum class Tool { Navigate, Incise, Suture, Fix, Patch, Remesh, Resect };

struct IncisionDraft {
  std::vector<engine::Vec3> points;
  bool snap = false;  ///< snap to edges ("snap") or cut through faces ("cut")
};

/// Resection: one click on the vessel wall per cut plane (resect_preview.hpp).
struct ResectDraft {
  std::vector<engine::Vec3> clicks;
  bool anastomosis = true;  ///< suture the two ends together (end-to-end anastomosis)
  float reach = 0.0f;       ///< mm, the op's `radius`; 0 = automatic
};

/// Two boundary chains, each named by clicking its two ends (suture_preview.hpp).
struct SutureDraft {
  std::vector<engine::Vec3> clicks;  ///< in click order; app::suture_sides reads them
  std::array<bool, 2> long_way = {false, false};  ///< per side: the longer arc between its ends
  bool onto_b = false;  ///< join placement onto_b: side A is drawn onto side B (a flap)
  /// The same point clicked twice on a cut: from one lip round to the other (suture_sides),
  /// not its whole loop.
  bool lip_to_lip = false;
};

/// Fix ends: a whole boundary loop per click, or a run of boundary vertices between two
/// clicks (following the boundary direction, mesh on the left).
struct FixDraft {
  bool run = false;
  std::vector<engine::Vec3> clicks;
};

struct PatchDraft {
  std::vector<engine::Vec3> ends;  ///< the two lip end points of the incision, in click order
  int shape = 0;                   ///< 0 ellipse, 1 diamond, 2 triangle
  float width = 4.0f;              ///< mm
  float youngs_modulus = 2.0f, poisson_ratio = 0.45f, thickness = 0.5f;
  /// Design the width instead (app::DesignTarget), the lumen measured along the incision
  /// between `ends`.
  bool target_z_score = false;      ///< the target: a diameter z-score, or else target_area
  float target_area = 20.0f;        ///< mm^2
  float z_score = -1.0f;
  float bsa_m2 = 0.2f;              ///< the child's body surface area
  int site = 1;                     ///< index into app::z_score_sites()
  float tolerance_percent = 5.0f;
  float width_min = 2.0f, width_max = 8.0f;  ///< mm
  float max_bulge = 1.4f;
};

/// Remesh: the faces within `radius` of the clicked points (of the whole object without
/// any) to `target_edge_length` (0 = their own mean), graded away from the points.
struct RemeshDraft {
  std::vector<engine::Vec3> points;
  float radius = 3.0f;               ///< mm
  float target_edge_length = 0.0f;   ///< mm, 0 = the region's mean edge length
  float grading = 1.0f;              ///< >= 1
  int iterations = 3;
  /// Or the faces within `small_angle_radius` (mm, along the edges) of a face with an angle
  /// below `below_angle` (degrees): where a solve sheared the mesh.
  float below_angle = 20.0f;
  float small_angle_radius = 0.6f;
};

/// The material of one region of the selected object: its first material (the wall) or a
/// patch's. The values are the region's own, loaded from the object whenever the object,
/// the region or the workspace changes, then edited until applied.
struct MaterialDraft {
  int region = 0;  ///< index into the object's materials: 0 the wall, others patches
  float youngs_modulus = 1.0f, poisson_ratio = 0.45f, thickness = 0.8f;
  /// The fields as loaded: a field still equal to its loaded value is not recorded, so a value
  /// the fields cannot show exactly (outside their range, more digits than a float) is kept.
  float loaded_youngs_modulus = 1.0f, loaded_poisson_ratio = 0.45f, loaded_thickness = 0.8f;
  std::size_t loaded_object = ~std::size_t{0};
  int loaded_region = -1;
  std::uint64_t loaded_revision = ~std::uint64_t{0};
};

struct SimulationSettings {
  int steps = 60;
  float dt = 1e-3f;
  /// Increments of s of a (static) relaxation. 3, as in the bundled arch sessions: fewer,
  /// larger increments cost less in all, for the same lumen (docs/performance.md,
  /// "Measurements behind defaults").
  int relax_steps = 3;
  bool collapse_barrier = false;  ///< records "collapse_barrier": true (session-format.md)
  /// The relaxation method: static (false), or the flap's static-then-damped-dynamics
  /// (flap_relaxation_ops; the relax steps above do not apply).
  bool staged_dynamics = false;
  /// After a run whose result has a triangle with an angle below the Remesh tool's limit
  /// (RemeshDraft::below_angle, within its small_angle_radius): remesh there and settle again
  /// (app::keep_angle_plan: one remesh per such object, then one solve), as more runs.
  bool keep_angle = true;
  /// A run with nothing to relax: a static solve of every load (app::static_solve_op), or
  /// (false) the implicit dynamics of `steps` steps of `dt`.
  bool static_settle = false;
};

struct Message {
  std::string text;
  bool error = false;    ///< shown in red: an error, or a warning
  bool warning = false;  ///< a warning (with `error`): labelled "Warning: " instead of "Error: "
};

struct GuiState {
  explicit GuiState(SessionController& c) : controller(c) {}

  SessionController& controller;
  StageMachine stages;
  OrbitCamera camera;
  WidgetRegistry widgets;
  ScenePicker picker;
  std::uint64_t picker_revision = ~std::uint64_t{0};
  ViewCache view;

  std::size_t object = 0;  ///< selected object (index into the workspace)
  Tool tool = Tool::Navigate;
  IncisionDraft incision;
  RemeshDraft remesh;
  SutureDraft suture;
  FixDraft fix;
  PatchDraft patch;
  ResectDraft resect;
  MaterialDraft material;
  /// The plan list: the runner's plan at revision plan_revision, and the step selected for
  /// inspection (an index into plan.steps; -1: none).
  app::Plan plan;
  std::uint64_t plan_revision = ~std::uint64_t{0};
  int plan_selected = -1;
  std::size_t plan_steps_shown = 0;  ///< steps when the list was last drawn (it scrolls to a new one)
  float pressure_mmhg = 80.0f;
  SimulationSettings simulation;
  /// Ops still to start, in order, once the running one has succeeded (the flap method's
  /// second phase; the keep-angle step's remeshes and settle); emptied when a run fails or is
  /// cancelled.
  std::deque<nlohmann::json> queued_runs;
  /// The runs Run simulation started end with the keep-angle step (SimulationSettings::
  /// keep_angle, keep_angle.hpp); while its runs go on (keeping_angle), the plan had
  /// keep_angle_plan_applied steps in effect before them.
  bool keep_angle_after_run = false;
  bool keeping_angle = false;
  std::size_t keep_angle_plan_applied = 0;
  std::vector<std::string> keep_angle_objects;  ///< the objects the step remeshes and settles
  /// The radius (mm) of the remesh of the running attempt: the Remesh tool's, or
  /// kWiderKeepAngleRadius times it in the second attempt (keep_angle_widened), after a run of
  /// the first failed (keep_angle.hpp).
  double keep_angle_radius = 0.0;
  bool keep_angle_widened = false;
  /// The running op: when it started, and its number among the runs the last Run simulation
  /// started (progress_text).
  std::chrono::steady_clock::time_point run_started;
  int run = 1, runs = 1;
  /// Starts `op` on the worker as run number `number` of `total`; false (and `why`) when it
  /// does not parse.
  bool start_run(const nlohmann::json& op, int number, int total, std::string& why);
  std::optional<Pick> hover;

  // Inspect.
  bool show_before = false;
  bool side_by_side = false;
  bool wireframe = false;
  /// Cut open (menu bar, View menu): what lies nearer the eye than a plane facing the view,
  /// through the orbit centre moved cut_offset_mm towards the eye, is neither drawn nor picked,
  /// so the lumen shows; a saved snapshot records the plane (its `clip`).
  bool cut_open = false;
  float cut_offset_mm = 0.0f;
  ViewField field = ViewField::None;
  /// Where the named open ends of every object are (the centroid of each boundary loop that
  /// app::end_name names), with their names; refreshed with the view.
  std::vector<std::pair<engine::Vec3, std::string>> end_labels;
  std::optional<engine::Vec3> plane_origin;
  /// The Cross-section controls are open: only then is the plane drawn over the view (a tool,
  /// not part of the plan: snapshots do not show it).
  bool section_controls_open = false;
  /// The cross-section plane's normal: 0 x, 1 y, 2 z; 3 across the vessel (perpendicular to
  /// its automatic centreline at plane_origin, through the lumen's middle there).
  int plane_axis = 3;
  /// The plane the Cross-section controls would measure (for plane_origin and plane_axis on
  /// the workspace at section_plane_key) and its half-size as drawn in the view, or why
  /// there is none (section_error).
  std::optional<engine::Plane> section_plane;
  double section_extent = 0.0;
  std::string section_error;
  std::string section_plane_key;
  /// The last measured section's outlines before and after, and its plane (the section
  /// view), with last_measure, while the workspace is still at last_section_revision
  /// (SessionController::workspace_revision; both dropped after a change).
  std::optional<app::SectionPair> last_section;
  engine::Plane last_section_plane;
  std::uint64_t last_section_revision = 0;
  nlohmann::json last_measure;
  /// Lumen profile: the open ends (boundary loops of the selected object, in loop order) it
  /// runs between, and the last profile's report details (null: none yet).
  int profile_from = 0, profile_to = 1;
  nlohmann::json last_profile;
  /// The last finished run's `equilibrium` report (null: none checked, e.g. plain dynamics).
  nlohmann::json last_equilibrium;
  int measure_count = 0;
  char snapshot_file[128] = "gui_snapshot.png";
  char export_file[128] = "meshes/result.obj";
  char template_file[128] = "patch_template.pdf";
  char report_file[128] = "plan_report.html";

  // Plan: opening and generating.
  char open_path[512] = "";
  /// Open the file as a segmentation export (the load's `prepare`): caps opened, remeshed.
  bool open_prepare = false;
  float prepare_edge_length = 0.0f;  ///< mm; 0: 16 edges around the narrowest end
  std::string browse_dir;
  char new_object[64] = "a";

  /// The message history, newest last, at most kMessageHistory (the oldest go first); errors
  /// stay until cleared.
  std::deque<Message> messages;
  static constexpr std::size_t kMessageHistory = 500;
  std::uint64_t messages_posted = 0;  ///< every message ever posted (the pane scrolls to a new one)
  std::uint64_t messages_shown = 0;   ///< messages_posted when the pane was last drawn
  float message_height = 80.0f;       ///< pixels; the user drags its top edge higher
  /// Thin rest triangles of the workspace at revision element_check_revision (refreshed with
  /// the picker): a run is refused or warned about, and the view marks them.
  app::ElementCheck element_check;
  /// The smallest angle of each object's shape shown, at the same revision (the Remesh tool
  /// shows the selected object's).
  std::vector<app::SmallestAngle> smallest_angles;
  std::uint64_t element_check_revision = ~std::uint64_t(0);
  /// selected_centreline(): made at revision centreline_revision for object centreline_object.
  std::optional<engine::CentrelineTree> centreline;
  std::string centreline_error;
  std::uint64_t centreline_revision = ~std::uint64_t(0);
  std::size_t centreline_object = 0;
  /// The Patch tool's preview of the patch op it would record now (patch_preview_key: that
  /// op, on the workspace at patch_preview_revision), or why it cannot be added
  /// (patch_preview_error).
  app::PatchPreview patch_preview;
  std::string patch_preview_error;
  std::string patch_preview_key;
  std::uint64_t patch_preview_revision = 0;
  /// Inspect's cutting-template op for the selected object and template_file (template_key)
  /// at template_revision, or why there is none (template_why): recomputed only when those
  /// change, not every frame (it copies the plan and scans the object's faces).
  nlohmann::json template_op;
  std::optional<std::string> template_why;
  std::string template_key;
  std::uint64_t template_revision = ~std::uint64_t(0);
  /// The Resect tool's preview for (resect_preview_key): recomputed only when that changes.
  app::ResectPreview resect_preview;
  std::string resect_preview_key;
  bool fit_requested = true;
  /// Applied after the fit: the camera looks from this standard view (View menu, view bar).
  std::optional<StandardView> view_requested;
  /// The 3-D view is the part of the window right of the workflow window (pixels from the
  /// left edge, set each frame by workflow_window) down to the bottom.
  float view_left = 0.0f;
  bool quit = false;
  /// The 3-D view's size in window pixels last frame (snapshots of the view take it).
  float view_width = 1000.0f, view_height = 800.0f;
  /// The part of the view's width the scene is drawn in (left of a legend's column), window
  /// pixels; picking and scripted clicks use it.
  float scene_width = 1000.0f;
  /// A snapshot op waiting for the answer to "replace the existing file?".
  std::optional<nlohmann::json> pending_snapshot;
  /// File > Open session: the session to go on with (replayed, then recorded to a new file in
  /// the output directory), once open_confirmed (open_dialog(): nothing would be lost, or the
  /// user said so) and no op runs; the frame loop switches before the next frame.
  std::optional<std::filesystem::path> open_requested;
  bool open_confirmed = false;
  bool open_announced = false;  ///< the "Opening ..." message has been shown for a frame
  char open_session_path[512] = "";
  /// Quit asked for (window closed, File > Quit, a script's quit): quits at once when nothing
  /// would be lost, otherwise asks first (quit_dialog()).
  bool quit_requested = false;

  /// What quitting now would lose (a drawn but uncommitted incision, suture, patch, resection,
  /// remesh or fix; a running simulation), one line each; empty when nothing. Every committed
  /// action is already in the recording.
  [[nodiscard]] std::vector<std::string> unsaved_work() const;

  [[nodiscard]] bool has_op(const std::string& name) const;
  /// Why an op this build lacks cannot be used, or nullopt when it exists.
  [[nodiscard]] std::optional<std::string> missing_op(const std::string& name) const;
  /// The stage gate for `a`, else missing_op(op) when op is non-empty.
  [[nodiscard]] std::optional<std::string> why_not(Command a, const std::string& op = {}) const;
  [[nodiscard]] const app::SceneObject* selected() const;
  /// The selected object's automatic centreline (app::tool_centreline of its current
  /// shape), made once per workspace_revision and object; nullptr (centreline_error says why)
  /// when there is no object or it cannot be made. Not while the controller is busy.
  const engine::CentrelineTree* selected_centreline();
  /// The camera the view shows: the orbit camera, backed off twice as far side by side (each
  /// half is half as wide, so the same objects still fit across it).
  [[nodiscard]] render::Camera shown_camera() const;
  /// The Cut open plane (render::ClipPlane: the side its normal points to, the eye's, is cut
  /// away), or nullopt when it is off.
  [[nodiscard]] std::optional<render::ClipPlane> clip_plane() const;

  void info(std::string text);
  void error(std::string text);
  /// A warning: in red like an error, labelled as a warning.
  void warn(std::string text);
  /// An op's warning (its report's "warning": a thin incision band and its cause, an uneven
  /// suture, a material out of range, ...), if any, as a warning (warn), in red until dismissed.
  void show_warning(const nlohmann::json& details);
  /// Records and runs `op` now (SessionController::run); reports the outcome as a message, and
  /// its warning (show_warning).
  /// True on success. (A snapshot op renders off-screen on the op thread: the window's GL
  /// context stays current on this one; only destroying a controller can take it away.)
  bool perform(const nlohmann::json& op, const std::string& done_text = {});
};

}  // namespace sutura::ui
