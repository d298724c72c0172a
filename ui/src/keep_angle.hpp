#pragma once
// The window's keep-angle step (SimulationSettings::keep_angle): after the runs that Run
// simulation started, remesh where the shape shown has an angle below the Remesh tool's limit
// and settle again (app::keep_angle_plan), as more runs. When one of its runs fails (the
// remesh or the settle), the step is taken back (undone, recorded as undo steps) and tried
// once more with a remesh of a wider region (kWiderKeepAngleRadius times the radius); when
// that fails too, or a run of the step is cancelled, it is taken back for good, so the user's
// run keeps its result.
#include <optional>
#include <string>

#include "gui_state.hpp"

namespace sutura::ui {

/// The second attempt's radius over the first's: the settle of a remeshed region that ends
/// across a steep strain gradient can fail where a slightly wider one converges
/// (docs/remeshing.md, the window's flap).
inline constexpr double kWiderKeepAngleRadius = 1.5;

/// Starts the keep-angle runs after `run`, the last of the runs Run simulation started, if the
/// workspace needs them; true when they started (the first running, the rest queued), with
/// s.keep_angle_objects the objects they remesh and settle. What the run reported (a warning
/// about its equilibrium; its equilibrium becomes s.last_equilibrium) is shown first. Errors
/// (the plan could not be made or started) are shown and give false.
bool start_keep_angle(GuiState& s, const ActionOutcome& run);

/// After `failed`, a run of the step that failed (not cancelled): takes the step back and, if
/// this was the first attempt and no cancel is pending, starts the second, with the wider
/// region (true); otherwise, or if the second cannot start, the step stays taken back, as
/// take_back_keep_angle says (false).
bool retry_keep_angle_wider(GuiState& s, const ActionOutcome& failed);

/// Undoes the keep-angle steps done so far (s.keeping_angle), after `what` happened to one of
/// its runs, and says so; the stage becomes Inspect with the shape the user's run left. If an
/// undo fails (its error is shown), the warning says that the remesh stays, unsettled.
void take_back_keep_angle(GuiState& s, const std::string& what);

/// After the keep-angle runs: the warning when one of the objects they remeshed still has an
/// angle below the limit (the numbers: where, and that face's rest angle), or nullopt.
std::optional<std::string> still_below_warning(const GuiState& s);

}  // namespace sutura::ui
