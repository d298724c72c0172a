#pragma once
// The one executor of session actions. `sutura replay` feeds it every action of a file in
// order; the GUI feeds it each action as the user makes it (after recording the action's
// line), so a replay of a GUI-recorded session runs exactly the code the GUI ran and ends on
// bit-identical meshes.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "sutura/app/plan.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"

namespace sutura::app {

class SessionRunner {
 public:
  /// Everything actions change: objects, probes, checks and the report's action and output
  /// lists. Opaque; taken by checkpoint(), put back by restore().
  struct Checkpoint;

  /// `session_file` names the session in messages and the report (relative `load` inputs
  /// were already resolved by the parser); `description` goes into the report. Creates
  /// options.out_dir. The clock of the report's timings starts here.
  SessionRunner(std::filesystem::path session_file, std::string description,
                ReplayOptions options);
  ~SessionRunner();
  SessionRunner(const SessionRunner&) = delete;
  SessionRunner& operator=(const SessionRunner&) = delete;

  /// Runs one action and returns what the report lists for it ("line", "op", "seconds" and
  /// the op's details), also appended to the report. On failure throws SessionError naming
  /// the action's line and op (OpCancelled's message when on_progress cancelled it) and
  /// records nothing; the workspace keeps what the op did before failing, as a replay
  /// reports it — callers that go on restore a checkpoint. Past options.time_limit nothing
  /// runs (SessionError; stopped()). After the op, a workspace beyond options.limits is an
  /// error.
  nlohmann::json execute(const Action& action);

  [[nodiscard]] const Workspace& workspace() const;
  [[nodiscard]] const ReplayOptions& options() const;
  /// The steps of the plan so far (plan.hpp), undone ones included. O(steps) copy.
  [[nodiscard]] Plan plan() const;
  /// How many actions so far changed the workspace (each plan step made, each undo and redo;
  /// not measurements, snapshots or reports): what is computed from the workspace is still
  /// good while this stands still. O(1).
  [[nodiscard]] std::uint64_t changes() const;
  /// options.time_limit has been reached: the action that was running stopped (its error says
  /// where) or the next one was not run.
  [[nodiscard]] bool stopped() const;
  /// The report.json content now, with `status` and (when non-empty) `error`.
  [[nodiscard]] nlohmann::json report(const std::string& status, const std::string& error = {}) const;
  /// Writes `report` atomically to out_dir/report.json.
  void write_report(const nlohmann::json& report);

  /// Copy of the state, undo history included (O(size of all meshes in it)); restore()
  /// returns to it exactly.
  [[nodiscard]] std::shared_ptr<const Checkpoint> checkpoint() const;
  void restore(const Checkpoint& checkpoint);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sutura::app
