#pragma once
// The planning workflow as a state machine: Plan -> Simulate -> Inspect (-> Plan again to
// continue on the result, as the paper's consecutive simulation runs allow).
//
// The GUI asks `why_disabled(command)` before enabling a button or menu item and shows the
// returned reason as its tooltip, so gating lives in one place and is unit-tested.
#include <optional>
#include <string>
#include <string_view>

namespace sutura::ui {

enum class Stage { Plan, Simulate, Inspect };

/// What the surgeon asks the window to do (a button or menu item), gated by stage; a command
/// may record session lines (app::Action), it is not one.
enum class Command {
  OpenMesh,
  Incise,
  Suture,
  AddPatch,
  Resect,
  Remesh,
  FixRegion,
  EditMaterial,
  Undo,
  Redo,
  StartSimulation,
  PauseResume,
  CancelSimulation,
  ToggleBeforeAfter,
  ShowColorMap,
  MeasureCrossSection,
  SaveSnapshot,
  ExportMesh,
  ContinuePlanning,
};

std::string_view to_string(Stage s);
std::string_view to_string(Command a);

class StageMachine {
 public:
  [[nodiscard]] Stage stage() const { return stage_; }
  [[nodiscard]] bool has_mesh() const { return has_mesh_; }

  /// Empty when `a` is allowed now; otherwise a sentence for the user saying why not.
  [[nodiscard]] std::optional<std::string> why_disabled(Command a) const;
  [[nodiscard]] bool allowed(Command a) const { return !why_disabled(a).has_value(); }

  // Events. Each throws std::logic_error when called while not allowed (a GUI bug, not a
  // user error: the GUI must have checked why_disabled first).
  void mesh_loaded();           ///< a mesh is open (Plan)
  void simulation_started();    ///< Plan -> Simulate
  void simulation_finished();   ///< Simulate -> Inspect
  void simulation_cancelled();  ///< Simulate -> Plan, state restored by the caller
  void continue_planning();     ///< Inspect -> Plan, on the simulated result

 private:
  void require(Command a) const;

  Stage stage_ = Stage::Plan;
  bool has_mesh_ = false;
};

}  // namespace sutura::ui
