#include "gui_command.hpp"

namespace sutura::app {

CLI::App* add_gui_command(CLI::App& app, ui::GuiOptions& options) {
  auto* gui = app.add_subcommand(
      "gui", "Open the planning window (Plan -> Simulate -> Inspect); every action is recorded "
             "to a session file that `sutura replay` reproduces");
  gui->add_option(
      "session", options.session,
      "Session to open: replayed to its last state, then continued in a new recording that "
      "starts as its copy (the session file itself is never written)");
  gui->add_option("-o,--out", options.out_dir,
                  "Output directory for snapshots, exports and new session files")
      ->capture_default_str();
  gui->add_option("--record", options.record,
                  "New session file to record into; never an existing one, which is refused "
                  "(default: OUT/session-<time>.jsonl, numbered when taken)");
  gui->add_option("--script", options.script,
                  "Scripted input for tests and benchmarks (see docs/gui.md)");
  gui->add_option("--width", options.width, "Window width")->capture_default_str();
  gui->add_option("--height", options.height, "Window height")->capture_default_str();
  gui->add_option("--msaa", options.samples,
                  "Anti-aliasing samples of the window (0 = off; 4 looks smoother on a GPU)")
      ->capture_default_str()
      ->check(CLI::Range(0, 16));
  gui->add_option("--threads", options.threads,
                  "Compute threads of the simulation (OpenMP and BLAS); default: one per core. "
                  "1 is faster where other processes keep the cores busy")
      ->check(CLI::Range(1, 1024));
  return gui;
}

}  // namespace sutura::app
