#pragma once
// `sutura gui [SESSION]`: the interactive planning window (GLFW + Dear ImGui over the same
// renderer as the headless snapshots). Every action is recorded to a session file as it
// happens and executed by the same SessionRunner as `sutura replay`.
#include <filesystem>

namespace sutura::ui {

struct GuiOptions {
  /// Existing session to open: replayed to its last state, then continued in the recording
  /// (which starts as a copy of it); the session file itself is never written. Empty: start
  /// with no objects.
  std::filesystem::path session;
  /// New session file to record into (never an existing one); empty = out_dir /
  /// "session-YYYYmmdd-HHMMSS.jsonl".
  std::filesystem::path record;
  std::filesystem::path out_dir = "out";  ///< snapshots, exports and report.json go inside
  /// Test hook: scripted input (docs/gui.md), injected through the same input queue as real
  /// events. The window quits when the script ends with {"quit": true}; a failing script
  /// step makes run_gui return 3.
  std::filesystem::path script;
  int width = 1400;
  int height = 900;
  /// Multisampling of the window (anti-aliasing). Off by default: on llvmpipe (CPU OpenGL)
  /// 4 samples cost about twice the frame time.
  int samples = 0;
  bool visible = true;
  /// Compute threads of the simulation (app::ReplayOptions::threads); 0 = one per core.
  int threads = 0;
};

/// Opens the window and runs until it is closed. Returns the process exit code: 0, 1 when
/// the session to open fails to replay (message on stderr), 3 when a script step fails.
/// Throws render::GlError when no display is available.
int run_gui(const GuiOptions& options);

}  // namespace sutura::ui
