#include "keep_angle.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include "sutura/app/element_check.hpp"
#include "sutura/app/op_builders.hpp"

namespace sutura::ui {

namespace {

double limit(const GuiState& s) { return app::as_typed(s.remesh.below_angle); }

}  // namespace

bool start_keep_angle(GuiState& s, const ActionOutcome& run) {
  std::vector<nlohmann::json> ops;
  std::string why;
  try {
    ops = app::keep_angle_plan(s.controller.workspace(), limit(s), app::as_typed(s.remesh.small_angle_radius),
                               s.simulation.collapse_barrier);
  } catch (const std::exception& e) {
    s.error(run.op + ": the remesh of small angles after the run could not be planned: " + e.what());
    return false;
  }
  if (ops.empty()) return false;
  // Everything read from the workspace is read now: once the first op runs on the worker, the
  // workspace is the worker's until it ends.
  std::vector<std::string> objects;
  for (const auto& name : ops.back()["objects"]) objects.push_back(name.get<std::string>());
  std::string text = run.op + " finished; smallest angle";
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
  text += ": remeshing there and settling again (Simulate: keep triangles well shaped)";
  const std::size_t applied = s.controller.plan().applied;
  try {
    if (!s.start_run(ops.front(), s.run + 1, s.run + int(ops.size()), why)) {
      s.error(run.op + ": the remesh of small angles after the run could not start: " + why);
      return false;
    }
  } catch (const std::exception& e) {
    s.error(run.op + ": the remesh of small angles after the run could not start: " + e.what());
    return false;
  }
  s.queued_runs.assign(ops.begin() + 1, ops.end());
  s.keeping_angle = true;
  s.keep_angle_plan_applied = applied;
  s.keep_angle_objects = objects;
  // The run's own verdict first: it stays the equilibrium shown if the step is taken back.
  s.last_equilibrium = run.details.value("equilibrium", nlohmann::json());
  if (run.details.contains("warning") && run.details["warning"].is_string())
    s.error("warning: " + run.details["warning"].get<std::string>());
  s.info(text);
  return true;
}

void take_back_keep_angle(GuiState& s, const std::string& what) {
  s.queued_runs.clear();
  s.keeping_angle = false;
  bool undone = true;
  while (undone && s.controller.plan().applied > s.keep_angle_plan_applied)
    undone = s.perform({{"op", "undo"}}, "Undone: the remesh of small angles");
  s.stages.simulation_finished();
  if (undone)
    s.error("warning: " + what +
            "; the remesh of small angles is taken back: the shape is the one the run left, with its small angles");
  else
    s.error("warning: " + what +
            "; the remesh of small angles could not be taken back (see the undo's error): the shape shown is "
            "remeshed but not settled, so it is no equilibrium. Undo it from Plan steps, or simulate again");
}

std::optional<std::string> still_below_warning(const GuiState& s) {
  std::vector<app::SmallestAngle> angles = app::smallest_angles(s.controller.workspace());
  std::erase_if(angles, [&](const app::SmallestAngle& a) {
    return std::find(s.keep_angle_objects.begin(), s.keep_angle_objects.end(), a.object) == s.keep_angle_objects.end();
  });
  const auto worst = std::min_element(angles.begin(), angles.end(),
                                      [](const auto& a, const auto& b) { return a.degrees < b.degrees; });
  if (worst == angles.end() || !(worst->degrees < limit(s))) return std::nullopt;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "after the remesh and the settle, '%s' still has an angle of %.1f degrees near (%.1f, %.1f, %.1f) "
                "mm, below %g; that face's rest shape has %.1f. Look at the membrane strain there.",
                worst->object.c_str(), worst->degrees, worst->where.x(), worst->where.y(), worst->where.z(), limit(s),
                worst->rest_degrees);
  return std::string(buf);
}

}  // namespace sutura::ui
