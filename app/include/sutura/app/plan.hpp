#pragma once
// The plan: the actions of a session that changed the workspace (edits, materials,
// constraints, loads, solves and runs; not snapshots, measurements or reports), oldest first,
// with what undo and redo did to them, and each in words for a surgeon. The GUI's plan list
// shows it; SessionRunner::plan() keeps it.
#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sutura::app {

struct PlanStep {
  int line = 0;           ///< the action's line in the session file
  std::string op;         ///< the op name
  nlohmann::json source;  ///< the action as written (Action::source)
  nlohmann::json result;  ///< what report.json lists for the action ("seconds", the op's details)
};

struct Plan {
  /// Every step made, oldest first. steps[0, applied) are in effect; the later ones were
  /// undone (redo brings back steps[applied] first; the next new step drops them, as it
  /// drops the redo history).
  std::vector<PlanStep> steps;
  std::size_t applied = 0;
  /// How many of the last applied steps undo can still take back: all of them unless the
  /// undo history's limits (limits.hpp) dropped the oldest states.
  std::size_t undoable = 0;
};

/// One line in words for an action as written, e.g. "Incise 'aorta' through 6 points, cut
/// through" or "Solve 'aorta' and make it the pre-operative shape"; the action's free-text
/// "note" is not part of it. Any op name gets a line (one this function does not know: its
/// name and object). O(1) but for the names of a solve's objects.
std::string describe_action(const nlohmann::json& source);

}  // namespace sutura::app
