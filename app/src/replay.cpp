#include "sutura/app/replay.hpp"

#include <chrono>
#include <iomanip>
#include <ostream>

#include "replay_run.hpp"

namespace sutura::app {

namespace fs = std::filesystem;
using nlohmann::json;

ReplayResult replay(const Session& session, const ReplayOptions& options) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto seconds_since = [](clock::time_point t) {
    return std::chrono::duration<double>(clock::now() - t).count();
  };

  detail::Run run{session, options, {}, {}, json::array(), json::array()};
  fs::create_directories(options.out_dir);
  const std::size_t n = session.actions.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Action& a = session.actions[i];
    const auto t0 = clock::now();
    if (options.progress)
      *options.progress << "[" << (i + 1) << "/" << n << "] line " << a.line << ": " << a.name
                        << std::flush;
    json details;
    try {
      details = std::visit(
          [&](const auto& op) -> json {
            if constexpr (std::is_same_v<std::decay_t<decltype(op)>, ReportOp>)
              return run.execute(op, seconds_since(start));
            else
              return run.execute(op);
          },
          a.op);
    } catch (const std::exception& e) {
      if (options.progress) *options.progress << " FAILED" << std::endl;
      const SessionError error(session.file.string(), a.line, a.name, "", e.what());
      try {
        run.write_report("report.json", run.report("failed", error.what(), seconds_since(start)));
      } catch (const std::exception&) {
        // The original error matters more than a report that could not be written.
      }
      throw error;
    }
    const double dt = seconds_since(t0);
    details["line"] = a.line;
    details["op"] = a.name;
    details["seconds"] = dt;
    run.actions.push_back(details);
    if (options.progress)
      *options.progress << " (" << std::fixed << std::setprecision(3) << dt << " s)"
                        << std::defaultfloat << std::endl;
  }
  ReplayResult result;
  result.report = run.report("ok", {}, seconds_since(start));
  run.write_report("report.json", result.report);
  result.report["outputs"] = run.outputs;
  result.workspace = std::move(run.workspace);
  return result;
}

}  // namespace sutura::app
