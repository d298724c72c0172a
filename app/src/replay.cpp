#include "sutura/app/replay.hpp"

#include <iomanip>
#include <ostream>
#include <sstream>

#include "sutura/app/session_runner.hpp"

namespace sutura::app {

using nlohmann::json;

ReplayResult replay(const Session& session, const ReplayOptions& options) {
  SessionRunner runner(session.file, session.description, options);
  const auto fail = [&](const SessionError& error) {
    try {
      runner.write_report(runner.report("failed", error.what()));
    } catch (const std::exception&) {
      // The original error matters more than a report that could not be written.
    }
  };
  try {
    check_limits(session, options.limits);
  } catch (const SessionError& error) {
    fail(error);
    throw;
  }
  const std::size_t n = session.actions.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Action& a = session.actions[i];
    if (options.progress)
      *options.progress << "[" << (i + 1) << "/" << n << "] line " << a.line << ": " << a.name
                        << std::flush;
    json details;
    try {
      details = runner.execute(a);
    } catch (const SessionError& error) {
      if (runner.stopped()) {  // the time limit: what was done is kept and reported
        if (options.progress) *options.progress << " STOPPED" << std::endl;
        ReplayResult result;
        result.stopped = true;
        std::ostringstream why;
        why << "the time limit of " << options.time_limit << " s was reached (--time-limit): " << error.what();
        result.report = runner.report("stopped", why.str());
        runner.write_report(result.report);
        result.workspace = runner.workspace();
        return result;
      }
      if (options.progress) *options.progress << " FAILED" << std::endl;
      fail(error);
      throw;
    }
    if (options.progress) {
      *options.progress << " (" << std::fixed << std::setprecision(3)
                        << details["seconds"].get<double>() << " s)" << std::defaultfloat
                        << std::endl;
      if (details.contains("values") && details["values"].contains("summary"))
        *options.progress << "    " << details["values"]["summary"].get<std::string>() << std::endl;
      if (details.contains("warning"))
        *options.progress << "    warning: " << details["warning"].get<std::string>() << std::endl;
    }
  }
  ReplayResult result;
  result.report = runner.report("ok");
  runner.write_report(result.report);
  result.report["outputs"] = runner.report("ok")["outputs"];
  result.workspace = runner.workspace();
  return result;
}

}  // namespace sutura::app
