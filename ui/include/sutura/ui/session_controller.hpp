#pragma once
// Turns GUI actions into session ops and runs them: every action is (1) parsed and checked,
// (2) appended to the recording session file and flushed, (3) executed by the same
// SessionRunner as `sutura replay`. A failed or cancelled action is taken back (workspace
// restored to its checkpoint, line removed from the file), so the file always replays to
// what the window shows.
//
// Every op runs on one long-lived op thread (op_thread.hpp: the same warm thread for all, as
// a headless replay runs all on one). run() and replay_existing() wait for it; the window
// start()s its simulation runs, and the main thread keeps drawing, reads the progress and
// live positions, and may pause, resume or cancel. While such an op runs, workspace() must
// not be read and no other op may start (busy() is true).
#include <atomic>
#include <condition_variable>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "sutura/app/session_runner.hpp"
#include "sutura/ui/op_thread.hpp"
#include "sutura/ui/session_recorder.hpp"

namespace sutura::ui {

/// What the worker reports while a long op runs (copied out under a lock).
struct LiveProgress {
  std::string op;          ///< op name, e.g. "simulate"
  std::string phase;       ///< RunProgress::phase
  int step = 0;
  int steps = 0;
  double fraction = 0.0;
  double s = -1.0;  ///< RunProgress::s: the relaxation's rest-shape parameter; -1 for plain dynamics
  double s_start = -1.0, s_end = -1.0;  ///< RunProgress::s_start, s_end
  bool paused = false;
  /// Latest positions by object name (only objects being simulated).
  std::vector<std::pair<std::string, std::vector<engine::Vec3>>> positions;
  std::uint64_t positions_revision = 0;  ///< increments whenever positions change
};

/// The outcome of one action.
struct ActionOutcome {
  std::string op;
  bool ok = false;
  bool cancelled = false;
  std::string message;  ///< error text when !ok
  nlohmann::json details;
};

class SessionController {
 public:
  /// `recorder` receives every action; `options` configure the runner (out_dir, ...).
  /// on_progress is owned by the controller.
  SessionController(SessionRecorder recorder, app::ReplayOptions options);
  ~SessionController();  ///< cancels and joins a running worker
  SessionController(const SessionController&) = delete;
  SessionController& operator=(const SessionController&) = delete;

  /// Runs the actions of an existing session (already in the recorder's file) to its last
  /// state, without recording them again. Throws SessionError when one fails.
  void replay_existing(const app::Session& session);

  /// Records `op`, runs it on the op thread and waits for it. Never throws for a bad op: the
  /// outcome says what went wrong (parse errors are not recorded at all). std::logic_error
  /// while busy().
  ActionOutcome run(const nlohmann::json& op);
  /// Records `op` and starts it on the op thread; false (and `why`) when it does not parse.
  /// std::logic_error while busy().
  bool start(const nlohmann::json& op, std::string& why);
  /// Main thread, once per frame: the outcome of a start()ed op that has ended, if any.
  std::optional<ActionOutcome> poll();

  /// Writes out_dir/report.json for the state now (the same content `sutura replay` of the
  /// recorded file writes, timings aside). Must not be called while busy(). Throws on I/O errors.
  void write_report();

  [[nodiscard]] bool busy() const { return running_; }
  void set_paused(bool paused);
  void cancel();  ///< asks the running op to stop; poll() then reports it cancelled
  /// cancel() was called since the last op started (also when it came after the op had
  /// finished but before poll() took its outcome: nothing that follows it should start).
  [[nodiscard]] bool cancel_requested() const { return cancel_.load(); }
  [[nodiscard]] LiveProgress progress() const;
  /// Counts what running ops have reported (each progress update, each end): while it stands
  /// still there is nothing new to draw. O(1), any thread.
  [[nodiscard]] std::uint64_t news() const { return news_.load(); }

  /// The objects; only while !busy(). revision() increments after every change.
  [[nodiscard]] const app::Workspace& workspace() const { return runner_.workspace(); }
  [[nodiscard]] std::uint64_t revision() const { return revision_; }
  /// Changes only when an op changed the objects (app::SessionRunner::changes), unlike
  /// revision(), which every op moves; only while !busy().
  [[nodiscard]] std::uint64_t workspace_revision() const { return runner_.changes(); }
  /// The plan's steps (app::SessionRunner::plan); only while !busy().
  [[nodiscard]] app::Plan plan() const { return runner_.plan(); }
  [[nodiscard]] const SessionRecorder& recorder() const { return recorder_; }
  [[nodiscard]] const app::ReplayOptions& options() const { return runner_.options(); }

 private:
  app::ReplayOptions with_hook(app::ReplayOptions options);
  bool on_progress(const app::RunProgress& p);
  // Appends and parses; nullopt (and the outcome's message) on a parse error.
  std::optional<app::Action> record(const nlohmann::json& op, ActionOutcome& outcome);
  ActionOutcome execute(const app::Action& action, const app::SessionRunner::Checkpoint& before);

  SessionRecorder recorder_;
  app::SessionRunner runner_;
  std::uint64_t revision_ = 0;

  bool running_ = false;  ///< a start()ed op has not been poll()ed yet
  std::shared_ptr<const app::SessionRunner::Checkpoint> worker_checkpoint_;
  std::optional<ActionOutcome> worker_outcome_;  ///< set by the worker before it ends
  std::atomic<bool> worker_done_{false};
  std::atomic<bool> cancel_{false};
  std::atomic<std::uint64_t> news_{0};
  mutable std::mutex mutex_;
  std::condition_variable resume_;
  bool paused_ = false;
  LiveProgress live_;
  OpThread ops_;  ///< last: destroyed first, waiting for an op that still runs
};

}  // namespace sutura::ui
