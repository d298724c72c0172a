#include "sutura/ui/session_controller.hpp"

#include <stdexcept>

namespace sutura::ui {

using nlohmann::json;

SessionController::SessionController(SessionRecorder recorder, app::ReplayOptions options)
    : recorder_(std::move(recorder)),
      runner_(recorder_.file(), "recorded by sutura gui", with_hook(std::move(options))) {}

SessionController::~SessionController() {
  if (running_) cancel();  // the OpThread's destructor then waits for the op to stop
}

app::ReplayOptions SessionController::with_hook(app::ReplayOptions options) {
  options.on_progress = [this](const app::RunProgress& p) { return on_progress(p); };
  return options;
}

bool SessionController::on_progress(const app::RunProgress& p) {
  std::unique_lock lock(mutex_);
  live_.phase = p.phase;
  live_.step = p.step;
  live_.steps = p.steps;
  live_.fraction = p.fraction;
  live_.s = p.s;
  live_.s_start = p.s_start;
  live_.s_end = p.s_end;
  live_.positions.clear();
  for (const auto& [name, x] : p.positions) live_.positions.emplace_back(name, std::vector(x.begin(), x.end()));
  ++live_.positions_revision;
  ++news_;
  // Pause: the solver waits here, between steps, until resumed or cancelled.
  resume_.wait(lock, [this] { return !paused_ || cancel_.load(); });
  return !cancel_.load();
}

void SessionController::replay_existing(const app::Session& session) {
  ops_.run([&] {
    for (const auto& a : session.actions) runner_.execute(a);
  });
  ++revision_;
}

std::optional<app::Action> SessionController::record(const json& op, ActionOutcome& outcome) {
  outcome.op = op.value("op", std::string("?"));
  const int line = recorder_.lines() + 1;
  try {
    app::Action action = app::parse_action(op, recorder_.file(), line, recorder_.format_version());
    if (recorder_.append(op) != line) throw std::logic_error("session line numbering mismatch");
    return action;
  } catch (const std::exception& e) {
    outcome.message = e.what();
    return std::nullopt;
  }
}

ActionOutcome SessionController::execute(const app::Action& action,
                                         const app::SessionRunner::Checkpoint& before) {
  ActionOutcome outcome;
  outcome.op = action.name;
  try {
    outcome.details = runner_.execute(action);
    outcome.ok = true;
    return outcome;
  } catch (const std::exception& e) {
    outcome.message = e.what();
    outcome.cancelled = cancel_.load();
  }
  runner_.restore(before);
  recorder_.drop_last();
  return outcome;
}

ActionOutcome SessionController::run(const json& op) {
  if (running_) throw std::logic_error("SessionController::run while an op runs");
  ActionOutcome outcome;
  const auto action = record(op, outcome);
  if (!action) return outcome;
  const auto before = runner_.checkpoint();
  ops_.run([&] { outcome = execute(*action, *before); });
  ++revision_;
  return outcome;
}

bool SessionController::start(const json& op, std::string& why) {
  if (running_) throw std::logic_error("SessionController::start while an op runs");
  ActionOutcome outcome;
  const auto action = record(op, outcome);
  if (!action) {
    why = outcome.message;
    return false;
  }
  worker_checkpoint_ = runner_.checkpoint();
  cancel_ = false;
  worker_done_ = false;
  {
    std::lock_guard lock(mutex_);
    paused_ = false;
    live_ = LiveProgress{};
    live_.op = action->name;
  }
  running_ = true;
  ops_.post([this, a = *action] {
    try {
      worker_outcome_ = execute(a, *worker_checkpoint_);
    } catch (const std::exception& e) {  // taking the failed op back failed (restore, the file)
      ActionOutcome o;
      o.op = a.name;
      o.message = std::string("the op failed and could not be taken back: ") + e.what();
      worker_outcome_ = o;
    }
    worker_done_ = true;
    ++news_;
  });
  return true;
}

std::optional<ActionOutcome> SessionController::poll() {
  if (!running_ || !worker_done_.load()) return std::nullopt;
  running_ = false;
  ops_.wait();
  worker_checkpoint_.reset();
  ++revision_;
  return std::exchange(worker_outcome_, std::nullopt);
}

void SessionController::write_report() {
  ops_.run([this] { runner_.write_report(runner_.report("ok")); });
}

void SessionController::set_paused(bool paused) {
  {
    std::lock_guard lock(mutex_);
    paused_ = paused;
    live_.paused = paused;
  }
  resume_.notify_all();
}

void SessionController::cancel() {
  {
    // Under the lock: a paused worker between checking its wait condition and sleeping would
    // otherwise miss the notification and sleep for ever.
    std::lock_guard lock(mutex_);
    cancel_ = true;
  }
  resume_.notify_all();
}

LiveProgress SessionController::progress() const {
  std::lock_guard lock(mutex_);
  return live_;
}

}  // namespace sutura::ui
