#include "sutura/app/session_runner.hpp"

#include <algorithm>

#include "replay_run.hpp"
#include "sutura/engine/compute_threads.hpp"

namespace sutura::app {

using nlohmann::json;
using clock_type = std::chrono::steady_clock;

struct SessionRunner::Checkpoint {
  Workspace workspace;
  json actions, outputs, probes, checks, measurements;
  std::vector<Workspace> undo_stack, redo_stack;
  Plan plan;
};

// The Run refers to the session header and options, so they live next to it at a fixed
// address (the Impl is never moved).
struct SessionRunner::Impl {
  Session header;
  ReplayOptions options;
  detail::Run run;
  clock_type::time_point start = clock_type::now();
  std::uint64_t changes = 0;  ///< changes()

  Impl(Session h, ReplayOptions o)
      : header(std::move(h)), options(std::move(o)),
        run{header, options, {}, {}, json::array(), json::array(),
            json::object(), json::array(), json::object(), {}, {}, 0, {}, {header.file}} {
    run.inputs.insert(run.inputs.end(), options.protected_inputs.begin(), options.protected_inputs.end());
    if (options.time_limit > 0)
      run.deadline = start + std::chrono::duration_cast<clock_type::duration>(
                                 std::chrono::duration<double>(options.time_limit));
  }
  [[nodiscard]] double elapsed() const {
    return std::chrono::duration<double>(clock_type::now() - start).count();
  }
};

SessionRunner::SessionRunner(std::filesystem::path session_file, std::string description,
                             ReplayOptions options) {
  Session header;
  header.file = std::move(session_file);
  header.description = std::move(description);
  std::filesystem::create_directories(options.out_dir);
  impl_ = std::make_unique<Impl>(std::move(header), std::move(options));
}

SessionRunner::~SessionRunner() = default;

json SessionRunner::execute(const Action& a) {
  detail::Run& run = impl_->run;
  const auto t0 = clock_type::now();
  if (impl_->options.threads > 0) engine::set_compute_threads(impl_->options.threads);
  json details;
  const std::uint64_t remembered = run.remembered;
  if (run.past_deadline())
    throw SessionError(impl_->header.file.string(), a.line, a.name, "", "not run");
  try {
    details = std::visit(
        [&](const auto& op) -> json {
          if constexpr (std::is_same_v<std::decay_t<decltype(op)>, ReportOp>)
            return run.execute(op, impl_->elapsed());
          else
            return run.execute(op);
        },
        a.op);
    run.check_workspace_limits();
    run.trim_history();
  } catch (const std::exception& e) {
    throw SessionError(impl_->header.file.string(), a.line, a.name, "", e.what());
  }
  details["line"] = a.line;
  details["op"] = a.name;
  details["seconds"] = std::chrono::duration<double>(clock_type::now() - t0).count();
  run.actions.push_back(details);
  if (run.remembered != remembered) {  // a step of the plan: it replaces the undone ones
    run.plan.steps.resize(run.plan.applied);
    run.plan.steps.push_back({a.line, a.name, a.source, details});
    run.plan.applied = run.plan.steps.size();
  }
  if (run.remembered != remembered || std::holds_alternative<UndoOp>(a.op) || std::holds_alternative<RedoOp>(a.op))
    ++impl_->changes;
  return details;
}

const Workspace& SessionRunner::workspace() const { return impl_->run.workspace; }

const ReplayOptions& SessionRunner::options() const { return impl_->options; }

Plan SessionRunner::plan() const {
  Plan p = impl_->run.plan;
  p.undoable = std::min(p.applied, impl_->run.undo_stack.size());
  return p;
}

std::uint64_t SessionRunner::changes() const { return impl_->changes; }

bool SessionRunner::stopped() const { return impl_->run.stopped; }

json SessionRunner::report(const std::string& status, const std::string& error) const {
  // The counts the report records are read on the calling thread: make them the run's.
  if (impl_->options.threads > 0) engine::set_compute_threads(impl_->options.threads);
  return impl_->run.report(status, error, impl_->elapsed());
}

void SessionRunner::write_report(const json& report) {
  impl_->run.write_report("report.json", report);
}

std::shared_ptr<const SessionRunner::Checkpoint> SessionRunner::checkpoint() const {
  const detail::Run& r = impl_->run;
  return std::make_shared<const Checkpoint>(Checkpoint{r.workspace, r.actions, r.outputs,
                                                      r.probes, r.checks, r.measurements,
                                                      r.undo_stack, r.redo_stack, r.plan});
}

void SessionRunner::restore(const Checkpoint& c) {
  detail::Run& r = impl_->run;
  r.workspace = c.workspace;
  r.actions = c.actions;
  r.outputs = c.outputs;
  r.probes = c.probes;
  r.checks = c.checks;
  r.measurements = c.measurements;
  r.undo_stack = c.undo_stack;
  r.redo_stack = c.redo_stack;
  r.plan = c.plan;
}

}  // namespace sutura::app
