#include "keep_angle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include "sutura/app/element_check.hpp"
#include "sutura/app/op_builders.hpp"

namespace sutura::ui {

namespace {

double limit(const GuiState& s) { return app::as_typed(s.remesh.below_angle); }
double first_radius(const GuiState& s) { return app::as_typed(s.remesh.small_angle_radius); }

std::string mm(double r) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g mm", r);
  return buf;
}

// Plans the step with a remesh within `radius` and starts its first run; `context` begins its
// messages, `why_now` ends its message, and `warning_first` (when not empty) is shown as a
// warning just before it. True when it started; false with an error shown, or without one when
// nothing is below the limit.
bool start_attempt(GuiState& s, const std::string& context, double radius, const std::string& why_now,
                   const std::string& warning_first = {}) {
  std::vector<nlohmann::json> ops;
  std::string why;
  try {
    ops = app::keep_angle_plan(s.controller.workspace(), limit(s), radius, s.simulation.collapse_barrier);
  } catch (const std::exception& e) {
    s.error(context + ": the remesh of small angles could not be planned: " + e.what());
    return false;
  }
  if (ops.empty()) return false;
  // Everything read from the workspace is read now: once the first op runs on the worker, the
  // workspace is the worker's until it ends.
  std::vector<std::string> objects;
  for (const auto& name : ops.back()["objects"]) objects.push_back(name.get<std::string>());
  std::string text = context + "; smallest angle";
  char buf[96];
  for (const app::SmallestAngle& a : app::smallest_angles(s.controller.workspace())) {
    if (std::find(objects.begin(), objects.end(), a.object) == objects.end()) continue;
    std::snprintf(buf, sizeof buf, " %.1f degrees", a.degrees);
    text += " of '";
    text += a.object;
    text += "':";
    text += buf;
  }
  std::snprintf(buf, sizeof buf, "%g", limit(s));
  text += ", below ";
  text += buf;
  text += ": " + why_now;
  const std::size_t applied = s.controller.plan().applied;
  try {
    if (!s.start_run(ops.front(), s.run + 1, s.run + int(ops.size()), why)) {
      s.error(context + ": the remesh of small angles could not start: " + why);
      return false;
    }
  } catch (const std::exception& e) {
    s.error(context + ": the remesh of small angles could not start: " + e.what());
    return false;
  }
  s.queued_runs.assign(ops.begin() + 1, ops.end());
  s.keeping_angle = true;
  s.keep_angle_plan_applied = applied;
  s.keep_angle_objects = objects;
  s.keep_angle_radius = radius;
  s.keep_angle_widened = radius != first_radius(s);
  if (!warning_first.empty()) s.warn(warning_first);
  s.info(text);
  return true;
}

// Undoes the step's applied plan steps; false when an undo failed (its error is shown).
bool undo_steps(GuiState& s) {
  bool undone = true;
  while (undone && s.controller.plan().applied > s.keep_angle_plan_applied)
    undone = s.perform({{"op", "undo"}}, "Undone: the remesh of small angles");
  return undone;
}

void say_taken_back(GuiState& s, const std::string& what, bool undone) {
  s.stages.simulation_finished();
  if (undone)
    s.warn(what +
           "; the remesh of small angles is taken back: the shape is the one the run left, with its small angles");
  else
    s.warn(what +
           "; the remesh of small angles could not be taken back (see the undo's error): the shape shown is "
           "remeshed but not settled, so it is no equilibrium. Undo it from Plan steps, or simulate again");
}

}  // namespace

bool start_keep_angle(GuiState& s, const ActionOutcome& run) {
  // The run's own verdict first: it stays the equilibrium shown if the step is taken back.
  const nlohmann::json& d = run.details;
  if (!start_attempt(s, run.op + " finished", first_radius(s),
                     "remeshing there and settling again (Simulate: keep triangles well shaped)",
                     d.contains("warning") && d["warning"].is_string() ? d["warning"].get<std::string>() : ""))
    return false;
  s.last_equilibrium = d.is_object() ? d.value("equilibrium", nlohmann::json()) : nlohmann::json();
  return true;
}

bool retry_keep_angle_wider(GuiState& s, const ActionOutcome& failed) {
  const std::string what = "its " + failed.op + " failed (" + failed.message + ")";
  const double first = first_radius(s);
  // Rounded to a micrometre, as typed: 1.5 x 0.6 records 0.9, not 0.8999999999999999.
  const double wider = std::round(kWiderKeepAngleRadius * first * 1e6) / 1e6;
  s.queued_runs.clear();
  s.keeping_angle = false;
  if (s.keep_angle_widened || s.controller.cancel_requested()) {  // the second attempt failed too
    say_taken_back(s, what, undo_steps(s));
    return false;
  }
  if (!undo_steps(s)) {
    say_taken_back(s, what, false);
    return false;
  }
  if (start_attempt(s, "the remesh of small angles within " + mm(first) + " failed at its " + failed.op + " (" +
                           failed.message + ")", wider,
                    "remeshing within " + mm(wider) + " instead and settling again"))
    return true;
  say_taken_back(s, what, true);
  return false;
}

void take_back_keep_angle(GuiState& s, const std::string& what) {
  s.queued_runs.clear();
  s.keeping_angle = false;
  say_taken_back(s, what, undo_steps(s));
}

std::optional<std::string> still_below_warning(const GuiState& s) {
  std::vector<app::SmallestAngle> angles = app::smallest_angles(s.controller.workspace());
  std::erase_if(angles, [&](const app::SmallestAngle& a) {
    return std::find(s.keep_angle_objects.begin(), s.keep_angle_objects.end(), a.object) == s.keep_angle_objects.end();
  });
  const std::optional<app::SmallestAngle> worst = app::worst_angle(angles);
  if (!worst || !(worst->degrees < limit(s))) return std::nullopt;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "after the remesh and the settle, '%s' still has an angle of %.1f degrees near (%.1f, %.1f, %.1f) "
                "mm, below %g; that face's rest shape has %.1f. Look at the membrane strain there.",
                worst->object.c_str(), worst->degrees, worst->where.x(), worst->where.y(), worst->where.z(), limit(s),
                worst->rest_degrees);
  return std::string(buf);
}

}  // namespace sutura::ui
