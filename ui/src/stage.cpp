#include "sutura/ui/stage.hpp"

#include <stdexcept>

namespace sutura::ui {

std::string_view to_string(Stage s) {
  switch (s) {
    case Stage::Plan: return "Plan";
    case Stage::Simulate: return "Simulate";
    case Stage::Inspect: return "Inspect";
  }
  return "?";
}

std::string_view to_string(Action a) {
  switch (a) {
    case Action::OpenMesh: return "open mesh";
    case Action::Incise: return "incise";
    case Action::Suture: return "suture";
    case Action::AddPatch: return "add patch";
    case Action::Resect: return "resect";
    case Action::Remesh: return "remesh";
    case Action::FixRegion: return "fix region";
    case Action::EditMaterial: return "edit material";
    case Action::Undo: return "undo";
    case Action::Redo: return "redo";
    case Action::StartSimulation: return "start simulation";
    case Action::PauseResume: return "pause/resume";
    case Action::CancelSimulation: return "cancel simulation";
    case Action::ToggleBeforeAfter: return "before/after";
    case Action::ShowColorMap: return "colour map";
    case Action::MeasureCrossSection: return "measure cross-section";
    case Action::SaveSnapshot: return "save snapshot";
    case Action::ExportMesh: return "export mesh";
    case Action::ContinuePlanning: return "continue planning";
  }
  return "?";
}

std::optional<std::string> StageMachine::why_disabled(Action a) const {
  const bool planning_edit = a == Action::Incise || a == Action::Suture || a == Action::AddPatch || a == Action::Resect ||
                             a == Action::Remesh || a == Action::FixRegion || a == Action::EditMaterial ||
                             a == Action::Undo || a == Action::Redo;
  const bool inspecting = a == Action::ToggleBeforeAfter || a == Action::ShowColorMap ||
                          a == Action::MeasureCrossSection || a == Action::ContinuePlanning;
  switch (stage_) {
    case Stage::Plan:
      if (a == Action::OpenMesh) return std::nullopt;
      if (!has_mesh_ && (planning_edit || a == Action::StartSimulation || a == Action::SaveSnapshot ||
                         a == Action::ExportMesh))
        return "Open a mesh first (File > Open, or the bundled aortic arch).";
      if (planning_edit || a == Action::StartSimulation || a == Action::SaveSnapshot ||
          a == Action::ExportMesh)
        return std::nullopt;
      if (a == Action::PauseResume || a == Action::CancelSimulation)
        return "No simulation is running.";
      if (inspecting) return "Available after a simulation, in the Inspect stage.";
      break;
    case Stage::Simulate:
      if (a == Action::PauseResume || a == Action::CancelSimulation) return std::nullopt;
      return "Not while the simulation runs: pause or cancel it first.";
    case Stage::Inspect:
      if (inspecting || a == Action::SaveSnapshot || a == Action::ExportMesh) return std::nullopt;
      if (a == Action::OpenMesh || planning_edit || a == Action::StartSimulation)
        return "Inspecting a result: choose Continue planning to edit it further.";
      if (a == Action::PauseResume || a == Action::CancelSimulation)
        return "No simulation is running.";
      break;
  }
  return "Not available in the " + std::string(to_string(stage_)) + " stage.";
}

void StageMachine::require(Action a) const {
  if (auto why = why_disabled(a))
    throw std::logic_error("'" + std::string(to_string(a)) + "' in stage " +
                           std::string(to_string(stage_)) + ": " + *why);
}

void StageMachine::mesh_loaded() {
  require(Action::OpenMesh);
  has_mesh_ = true;
}

void StageMachine::simulation_started() {
  require(Action::StartSimulation);
  stage_ = Stage::Simulate;
}

void StageMachine::simulation_finished() {
  if (stage_ != Stage::Simulate) throw std::logic_error("simulation_finished outside Simulate");
  stage_ = Stage::Inspect;
}

void StageMachine::simulation_cancelled() {
  require(Action::CancelSimulation);
  stage_ = Stage::Plan;
}

void StageMachine::continue_planning() {
  require(Action::ContinuePlanning);
  stage_ = Stage::Plan;
}

}  // namespace sutura::ui
