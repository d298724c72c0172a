#pragma once
// The ImGui panels: menu bar, the workflow window (Plan / Simulate / Inspect sections, each
// action gated by the stage machine and by the ops this build has) and the message line.
#include "gui_state.hpp"

namespace sutura::ui {

void menu_bar(GuiState& s);
/// The left-hand workflow window.
void workflow_window(GuiState& s);
void plan_section(GuiState& s);
void simulate_section(GuiState& s);
void inspect_section(GuiState& s);
/// Inspect > Cross-section: the plane's placement, the measure op, and the section view.
void cross_section_controls(GuiState& s);
/// The plan list (in the Plan section): every step that changed the workspace, in words;
/// the selected one shows what was recorded and what it did, and the last can be undone.
void plan_steps(GuiState& s);
/// A quit asked for: quits when nothing would be lost, otherwise a modal dialog lists what
/// would be and offers "Quit anyway" and "Keep planning".
void quit_dialog(GuiState& s);
/// File > Open session asked for: confirms at once when nothing would be lost, otherwise a
/// modal dialog lists what would be and offers "Open anyway" and "Keep planning".
void open_dialog(GuiState& s);
/// Messages at the bottom of the window: errors in red, dismissable.
void message_window(GuiState& s);
/// The view cube in the 3-D view's top-left corner (kViewCubeCorner pixels square, below the
/// menu bar): a cube turned as the camera is, its faces named A, P, L, R, S, I (anterior ...
/// inferior, the patient frame of docs/anatomy.md); clicking a face looks from there, as
/// View from does. Each face seen head-on or obliquely (not edge-on: more than a fifth of
/// its area showing) is noted as "view cube " + to_string(view); the square takes every
/// click inside it.
void view_cube(GuiState& s);
inline constexpr float kViewCubeCorner = 112.0f;

/// Commits the incision draft (Enter in the view); no-op with a message when incomplete.
void commit_incision(GuiState& s);
/// Commits the suture draft as a join op.
void commit_suture(GuiState& s);
/// The Resect tool's panel, and its commit (Enter in the view).
void resect_controls(GuiState& s);
void commit_resection(GuiState& s);
/// Escape: drops the active tool's draft.
void cancel_draft(GuiState& s);
/// Ctrl+Z / Ctrl+Y.
void undo(GuiState& s);
void redo(GuiState& s);

}  // namespace sutura::ui
