// The Simulate section: run settings, start on the worker thread, progress, pause/cancel.
#include "panels.hpp"
#include "progress_text.hpp"
#include "sutura/app/session.hpp"
#include "sutura/app/simulation.hpp"

namespace sutura::ui {

namespace {

// Why the simulate op with relaxation does not parse in this build (the `relax` field comes
// with the surgery ops), or nullopt.
std::optional<std::string> relax_unsupported() {
  try {
    app::parse_action(app::simulate_op(1, 1e-3, 1), "probe.jsonl", 1);
    return std::nullopt;
  } catch (const std::exception&) {
    return "Not available in this build: the simulate op has no 'relax' field yet.";
  }
}

// Relaxation needs a suture made since the last relaxing run.
std::optional<std::string> nothing_to_relax(const GuiState& s) {
  if (s.controller.busy()) return std::nullopt;
  for (const auto& o : s.controller.workspace().objects())
    if (app::has_pending_relaxation(o)) return std::nullopt;
  return "No suture since the last relaxation: the run only settles.";
}

// The runs Run simulation starts, in order: the flap method's two, one relaxation, or with
// nothing to relax (relax 0) a static solve or implicit dynamics.
std::vector<nlohmann::json> run_ops(const GuiState& s, int relax) {
  const SimulationSettings& o = s.simulation;
  if (relax > 0 && o.staged_dynamics) return app::flap_relaxation_ops(o.collapse_barrier);
  if (relax == 0 && o.static_settle)
    return {app::static_solve_op(app::loads_have_potential(s.controller.workspace()), o.collapse_barrier)};
  return {app::simulate_op(o.steps, o.dt, relax, o.collapse_barrier)};
}

}  // namespace

void simulate_section(GuiState& s) {
  static const std::optional<std::string> unsupported = relax_unsupported();
  const bool running = s.controller.busy();
  const std::optional<std::string> no_relax = unsupported ? unsupported : nothing_to_relax(s);
  ImGui::BeginDisabled(running);
  // A relaxing run is static (Newton per increment of s, then a settling solve): the dynamics
  // settings below only drive a run with nothing to relax, so only the settings that apply
  // are enabled.
  ImGui::BeginDisabled(no_relax.has_value());
  if (noted_radio(s.widgets, "Static relaxation", !s.simulation.staged_dynamics))
    s.simulation.staged_dynamics = false;
  tooltip_for_last_item("Newton solves at increasing s: fast, and enough for patches, "
                        "resections and most sutures.");
  if (noted_radio(s.widgets, "Static, then damped dynamics (flap)", s.simulation.staged_dynamics)) {
    s.simulation.staged_dynamics = true;
    s.simulation.collapse_barrier = true;  // a flap gathers tissue (see the box below)
  }
  tooltip_for_last_item(
      "For a flap turned down into an aortotomy (subclavian flap aortoplasty): static to "
      "s = 0.6, then damped dynamics, whose inertia carries the gathered flap through its "
      "buckling, then a static settle. Two runs, one after the other.");
  ImGui::BeginDisabled(s.simulation.staged_dynamics);
  number_field("relax steps", &s.simulation.relax_steps, 1, 100);
  ImGui::EndDisabled();
  ImGui::EndDisabled();
  tooltip_for_last_item(no_relax ? *no_relax
                        : s.simulation.staged_dynamics
                            ? "The flap method has its own steps: 16 static to s = 0.6, then 80 + 40 dynamic."
                            : "Increments of s (rest shape from the joined to the split "
                                   "shape). Fewer, larger increments usually need fewer Newton "
                                   "iterations in all; more give more frames of the animation.");
  ImGui::BeginDisabled(!no_relax.has_value());
  if (noted_radio(s.widgets, "Static equilibrium", s.simulation.static_settle)) s.simulation.static_settle = true;
  tooltip_for_last_item("With nothing to relax: the shape in equilibrium under every load (e.g. 80 mmHg once the "
                        "clamps are off), in 4 load steps; as an energy minimisation when the loads have one.");
  ImGui::SameLine();
  if (noted_radio(s.widgets, "Implicit dynamics", !s.simulation.static_settle)) s.simulation.static_settle = false;
  tooltip_for_last_item("With nothing to relax: the settle steps below, each dt long.");
  ImGui::BeginDisabled(s.simulation.static_settle);
  number_field("settle steps", &s.simulation.steps, 1, 400);
  tooltip_for_last_item("Implicit dynamics steps of a run with nothing to relax.");
  ImGui::InputFloat("dt [s]", &s.simulation.dt, 0.0f, 0.0f, "%.4f");
  ImGui::EndDisabled();
  ImGui::EndDisabled();
  noted_checkbox(s.widgets, "Resist collapse (gathered tissue)", &s.simulation.collapse_barrier);
  tooltip_for_last_item(
      "Adds the collapse barrier: triangles resist being squashed below a quarter of their rest "
      "area. Needed where a suture gathers tissue more finely than the mesh can wrinkle "
      "(e.g. a subclavian flap).");
  noted_checkbox(s.widgets, "Keep triangles well shaped", &s.simulation.keep_angle);
  tooltip_for_last_item(
      "After the run, where a triangle of the result has an angle below the Remesh tool's limit "
      "(20 degrees unless changed there): remesh the faces around it (within the tool's distance) "
      "and settle again (an energy minimisation where the loads have one). More steps of the plan, "
      "recorded as such; taken back if the settle fails or is cancelled. Objects not held are left as they are.");
  ImGui::EndDisabled();

  if (!running) {
    const auto coloured = [](ImVec4 colour, const std::string& text) {
      ImGui::PushStyleColor(ImGuiCol_Text, colour);
      ImGui::TextWrapped("%s", text.c_str());
      ImGui::PopStyleColor();
    };
    if (const auto refusal = s.element_check.refusal())
      coloured(ImVec4(0.75f, 0.05f, 0.05f, 1.0f), *refusal);
    else if (const auto warning = s.element_check.warning())
      coloured(ImVec4(0.7f, 0.4f, 0.0f, 1.0f), *warning);
  }
  if (gated_button(s.widgets, "Run simulation", s.why_not(Command::StartSimulation, "simulate"),
                   "Relax the rest shape (s from 0 to 1), then settle; runs in the background.")) {
    const int relax = no_relax ? 0 : s.simulation.relax_steps;
    std::string why;
    if (const auto refusal = s.element_check.refusal()) {
      s.error("Run refused. " + *refusal);
    } else if (std::vector<nlohmann::json> ops = run_ops(s, relax); s.start_run(ops.front(), 1, int(ops.size()), why)) {
      s.queued_runs.assign(ops.begin() + 1, ops.end());
      s.keep_angle_after_run = s.simulation.keep_angle;
      s.stages.simulation_started();
      s.tool = Tool::Navigate;
      cancel_draft(s);
    } else {
      s.error("simulate: " + why);
    }
  }
  if (running) {
    const LiveProgress p = s.controller.progress();
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - s.run_started).count();
    const ProgressText text = progress_text(p, elapsed, s.run, s.runs);
    ImGui::ProgressBar(float(text.fraction), ImVec2(-1, 0), text.bar.c_str());
    ImGui::TextWrapped("%s", text.detail.c_str());
    if (gated_button(s.widgets, p.paused ? "Resume" : "Pause", s.why_not(Command::PauseResume)))
      s.controller.set_paused(!p.paused);
    ImGui::SameLine();
    if (gated_button(s.widgets, "Cancel simulation", s.why_not(Command::CancelSimulation),
                     "Stop and restore the state before the run."))
      s.controller.cancel();
  } else {
    ImGui::TextDisabled("No simulation running.");
  }
}

}  // namespace sutura::ui
