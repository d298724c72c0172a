#pragma once
// A session controller recording into a scratch directory of its own (removed afterwards), for
// the tests of the window's action path without a window.
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <unistd.h>

#include "sutura/app/replay.hpp"
#include "sutura/ui/session_controller.hpp"

namespace sutura::testing {

struct ControllerFixture {
  std::filesystem::path dir;
  std::unique_ptr<ui::SessionController> controller;
  /// `name` makes the directory's name (with the process id); `threads` as ReplayOptions.
  explicit ControllerFixture(const std::string& name, int threads = 0) {
    dir = std::filesystem::temp_directory_path() / ("sutura_ctl_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    app::ReplayOptions o;
    o.out_dir = dir / "out";
    o.threads = threads;
    controller = std::make_unique<ui::SessionController>(ui::SessionRecorder::create(dir / "rec.jsonl", "test"), o);
  }
  ~ControllerFixture() { std::filesystem::remove_all(dir); }
  ControllerFixture(const ControllerFixture&) = delete;
  ControllerFixture& operator=(const ControllerFixture&) = delete;
  /// The outcome of the op on the worker, waited for up to a minute (nullopt: still running).
  std::optional<ui::ActionOutcome> wait() {
    std::optional<ui::ActionOutcome> outcome;
    for (int i = 0; i < 12000 && !outcome; ++i) {
      outcome = controller->poll();
      if (!outcome) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return outcome;
  }
};

}  // namespace sutura::testing
