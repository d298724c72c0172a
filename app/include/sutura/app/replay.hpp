#pragma once
// Headless replay of a session: runs every action in order, writes PNGs, meshes and
// report.json inside the output directory, and reports progress.
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "sutura/app/limits.hpp"
#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"

namespace sutura::app {

/// Where a long-running op (simulate) stands; see ReplayOptions::on_progress.
struct RunProgress {
  std::string phase;      ///< "simulate" (the lead's relaxation adds "relax" / "settle")
  int step = 0;           ///< steps done so far in this op
  int steps = 0;          ///< steps planned in this op
  double fraction = 0.0;  ///< of the whole op, [0, 1]
  double s = -1.0;         ///< relaxation parameter reached, [0, 1]; -1 for plain dynamics
  /// The relaxation's range of s: where it started (a later run continues from the s an
  /// earlier one stopped at) and where it stops (`until`); -1 for plain dynamics.
  double s_start = -1.0, s_end = -1.0;
  double residual = -1.0;  ///< static residual |r| over free DOFs, N; -1 when not computed
  int newton_iterations = -1;  ///< of the last relaxation increment; -1 when not counted
  int quasi_newton_iterations = 0;  ///< of the last relaxation increment (reused factorisations)
  /// Current positions of every object the op simulates, by name; the spans are valid only
  /// during the callback (copy what you keep).
  std::vector<std::pair<std::string, std::span<const engine::Vec3>>> positions;
};

/// Thrown by an op whose ReplayOptions::on_progress returned false. The op's objects hold the
/// state reached when it stopped; callers that cancel restore a SessionRunner checkpoint.
class OpCancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReplayOptions {
  std::filesystem::path out_dir = "out";  ///< every output goes inside; created if missing
  /// Files no output may write besides the session itself and the meshes it reads (the GUI:
  /// the session it opened and continues in a new recording).
  std::vector<std::filesystem::path> protected_inputs;
  std::ostream* progress = nullptr;       ///< one line per action; nullptr = silent
  /// Called by long ops before each step, on the thread running the op (the GUI's worker);
  /// may block (pause). Return false to cancel the op (it then throws OpCancelled).
  /// Empty: never called.
  std::function<bool(const RunProgress&)> on_progress;
  /// Compute threads (OpenMP and OpenBLAS, engine::set_compute_threads), set before every op
  /// on the thread that runs it (the GUI runs long ops on a worker thread, and OpenMP's count
  /// is per thread); 0 = leave them as they are (one per core unless the environment says
  /// otherwise). Position hashes depend on it; the report records it.
  int threads = 0;
  /// Bounds on the work the session may ask for (limits.hpp), checked before it runs and as
  /// it runs.
  Limits limits;
  /// Seconds, > 0: the run stops cleanly when this much time has passed, between ops or
  /// inside a long one (dynamics, relaxation), with report.json written and status
  /// "stopped"; 0 = no limit.
  double time_limit = 0.0;
};

struct ReplayResult {
  Workspace workspace;   ///< final state of every object
  nlohmann::json report; ///< the content written to out_dir/report.json
  bool stopped = false;  ///< the time limit ended the run (report status "stopped")
};

/// Runs `session` after checking it against options.limits. On success writes
/// out_dir/report.json with status "ok". When options.time_limit ends it, writes status
/// "stopped" with the line it stopped at and returns (result.stopped). On failure (a limit
/// included) writes out_dir/report.json with status "failed" and the error (what was done up
/// to then is kept), then throws SessionError naming the line and op that failed.
ReplayResult replay(const Session& session, const ReplayOptions& options);

}  // namespace sutura::app
