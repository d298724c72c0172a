#pragma once
#include <array>
// The state of one replay and the execution of every op on it. replay.cpp runs the loop;
// replay_scene_ops.cpp and replay_simulation_ops.cpp execute the two op families.
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "snapshot.hpp"
#include "sutura/app/plan.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/simulation.hpp"

namespace sutura::app::detail {

using nlohmann::json;

// Mutable state of one replay: the objects, the report being built and the renderer.
struct Run {
  const Session& session;
  const ReplayOptions& options;
  Workspace workspace;
  SnapshotRenderer snapshots;
  json actions = json::array();
  json outputs = json::array();
  json probes = json::object();
  json checks = json::array();
  json measurements = json::object();
  // Undo/redo: the workspace before each change (edits, constraints, loads, runs).
  std::vector<Workspace> undo_stack;
  std::vector<Workspace> redo_stack;
  /// remember() calls so far: SessionRunner::execute adds a plan step for an action that made one.
  std::uint64_t remembered = 0;
  /// The steps the undo and redo stacks hold (plan.hpp); undo and redo move plan.applied.
  Plan plan;
  /// Pushes the current workspace for undo and clears redo; called by every changing op
  /// before it takes an object to edit.
  void remember();
  /// Drops the oldest undo states until the history holds at most kMaxUndo states and
  /// options.limits.undo_megabytes of objects that the current workspace does not share;
  /// called after every op.
  void trim_history();

  // Files this run reads: the session (first) and every loaded mesh. No output may
  // overwrite one.
  std::vector<std::filesystem::path> inputs;

  // Limits (options.limits, options.time_limit; limits.hpp).
  /// States dropped from the bottom of the undo history to keep it within
  /// options.limits.undo_megabytes (undo says so when it reaches them).
  std::size_t undo_dropped = 0;
  // options.time_limit from the start of the run (max when none); `stopped` once reached.
  std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max();
  bool stopped = false;
  /// True (and `stopped` set) once the deadline has passed.
  bool past_deadline();
  /// Throws std::runtime_error naming the limit when the workspace exceeds
  /// options.limits.faces_per_object, faces_in_all or objects.
  void check_workspace_limits() const;

  // Output bookkeeping and the report (replay_scene_ops.cpp). `output` throws
  // std::invalid_argument for a path outside the output directory or one that is an input.
  std::filesystem::path output(const std::filesystem::path& relative);
  /// The named object, to read / to change (copied first if the undo history shares it;
  /// see Workspace::edit). Both throw std::runtime_error naming the objects there are.
  const SceneObject& object(const std::string& name) const;
  SceneObject& edit(const std::string& name);
  json report(const std::string& status, const std::string& error, double total) const;
  void write_report(const std::filesystem::path& relative, const json& r);

  // Scene ops (replay_scene_ops.cpp).
  json execute(const GenerateOp& op);
  json execute(const LoadOp& op);
  json execute(const SnapshotOp& op);
  json execute(const ExportOp& op);
  json execute(const ExportPatchTemplateOp& op);
  json execute(const ReportOp& op, double elapsed);
  json execute(const PlanReportOp& op);

  // Simulation ops (replay_simulation_ops.cpp).
  std::vector<engine::VertexId> resolve(const SceneObject& obj, const VertexSelection& sel);
  std::vector<SceneObject*> objects_named(const std::vector<std::string>& names);
  /// Orders boundary vertices `ids` along their boundary loop; they must be one contiguous run.
  std::vector<engine::VertexId> boundary_chain(const SceneObject& obj,
                                               const std::vector<engine::VertexId>& ids);
  json execute(const MaterialOp& op);
  json execute(const ConstrainOp& op);
  json execute(const ForceOp& op);
  json execute(const LineLoadOp& op);
  json execute(const PressureOp& op);
  json execute(const BodyForceOp& op);
  json execute(const SolveOp& op);
  json execute(const UnloadOp& op);
  json execute(const SimulateOp& op);
  /// Passes a long op's progress (step of steps, current merged positions `x`, and for a
  /// relaxation its s, range of s, residual and Newton iterations) to options.on_progress;
  /// false when the caller asks to cancel.
  bool report_progress(const std::string& phase, int step, int steps, const MergedSystem& merged,
                       const std::vector<engine::Vec3>& x, double s = -1.0,
                       double residual = -1.0, int newton_iterations = -1,
                       int quasi_newton_iterations = 0, std::array<double, 2> s_range = {-1.0, -1.0});
  json execute(const ProbeOp& op);
  json execute(const CheckOp& op);

  // Surgery ops (replay_surgery_ops.cpp).
  json execute(const InciseOp& op);
  json execute(const JoinOp& op);
  json execute(const PatchOp& op);
  json execute(const ResectOp& op);
  json execute(const RemeshOp& op);
  json execute(const MeasureOp& op);
  // design_patch (replay_design_patch.cpp): candidates of patch + simulate + measure.
  json execute(const DesignPatchOp& op);
  json execute(const DistanceOp& op);
  json execute(const UndoOp& op);
  json execute(const RedoOp& op);
  /// Simulate with rest-shape relaxation of the objects' pending sutures.
  json relax(const SimulateOp& op);
};

}  // namespace sutura::app::detail
