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

std::string_view to_string(Command a) {
  switch (a) {
    case Command::OpenMesh: return "open mesh";
    case Command::Incise: return "incise";
    case Command::Suture: return "suture";
    case Command::AddPatch: return "add patch";
    case Command::Resect: return "resect";
    case Command::Remesh: return "remesh";
    case Command::FixRegion: return "fix region";
    case Command::EditMaterial: return "edit material";
    case Command::Undo: return "undo";
    case Command::Redo: return "redo";
    case Command::StartSimulation: return "start simulation";
    case Command::PauseResume: return "pause/resume";
    case Command::CancelSimulation: return "cancel simulation";
    case Command::ToggleBeforeAfter: return "before/after";
    case Command::ShowColorMap: return "colour map";
    case Command::MeasureCrossSection: return "measure cross-section";
    case Command::SaveSnapshot: return "save snapshot";
    case Command::ExportMesh: return "export mesh";
    case Command::ContinuePlanning: return "continue planning";
  }
  return "?";
}

std::optional<std::string> StageMachine::why_disabled(Command a) const {
  const bool planning_edit = a == Command::Incise || a == Command::Suture || a == Command::AddPatch || a == Command::Resect ||
                             a == Command::Remesh || a == Command::FixRegion || a == Command::EditMaterial ||
                             a == Command::Undo || a == Command::Redo;
  const bool inspecting = a == Command::ToggleBeforeAfter || a == Command::ShowColorMap ||
                          a == Command::MeasureCrossSection || a == Command::ContinuePlanning;
  switch (stage_) {
    case Stage::Plan:
      if (a == Command::OpenMesh) return std::nullopt;
      if (!has_mesh_ && (planning_edit || a == Command::StartSimulation || a == Command::SaveSnapshot ||
                         a == Command::ExportMesh))
        return "Open a mesh first (File > Open, or the bundled aortic arch).";
      if (planning_edit || a == Command::StartSimulation || a == Command::SaveSnapshot ||
          a == Command::ExportMesh)
        return std::nullopt;
      if (a == Command::PauseResume || a == Command::CancelSimulation)
        return "No simulation is running.";
      if (inspecting) return "Available after a simulation, in the Inspect stage.";
      break;
    case Stage::Simulate:
      if (a == Command::PauseResume || a == Command::CancelSimulation) return std::nullopt;
      return "Not while the simulation runs: pause or cancel it first.";
    case Stage::Inspect:
      if (inspecting || a == Command::SaveSnapshot || a == Command::ExportMesh) return std::nullopt;
      if (a == Command::OpenMesh || planning_edit || a == Command::StartSimulation)
        return "Inspecting a result: choose Continue planning to edit it further.";
      if (a == Command::PauseResume || a == Command::CancelSimulation)
        return "No simulation is running.";
      break;
  }
  return "Not available in the " + std::string(to_string(stage_)) + " stage.";
}

void StageMachine::require(Command a) const {
  if (auto why = why_disabled(a))
    throw std::logic_error("'" + std::string(to_string(a)) + "' in stage " +
                           std::string(to_string(stage_)) + ": " + *why);
}

void StageMachine::mesh_loaded() {
  require(Command::OpenMesh);
  has_mesh_ = true;
}

void StageMachine::simulation_started() {
  require(Command::StartSimulation);
  stage_ = Stage::Simulate;
}

void StageMachine::simulation_finished() {
  if (stage_ != Stage::Simulate) throw std::logic_error("simulation_finished outside Simulate");
  stage_ = Stage::Inspect;
}

void StageMachine::simulation_cancelled() {
  require(Command::CancelSimulation);
  stage_ = Stage::Plan;
}

void StageMachine::continue_planning() {
  require(Command::ContinuePlanning);
  stage_ = Stage::Plan;
}

}  // namespace sutura::ui
