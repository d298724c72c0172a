#pragma once
// What the Simulate panel says about a running op: the phase in plain words, how far it has
// got on a scale that does not jump (the rest-shape parameter s of a relaxation, whose planned
// step count changes as increments are halved or doubled; the steps of plain dynamics), and
// an estimate of the time left from the pace so far. Pure: a function of the progress and
// the clock, tested without a window.
#include <string>

#include "sutura/ui/session_controller.hpp"

namespace sutura::ui {

struct ProgressText {
  std::string bar;      ///< on the progress bar
  std::string detail;   ///< the line below it: elapsed, estimate, phase of a multi-run plan
  double fraction = 0;  ///< fill of the bar, [0, 1]
};

/// `elapsed` seconds since the op started; `run` and `runs` number the ops of a plan that
/// starts several (the flap method: 2), 1 and 1 otherwise. A relaxation fills the bar by s over
/// its range [p.s_start, p.s_end] (a run continued from s = 0.6, one that stops at `until`).
/// The estimate is given once 5 % of the way and 2 s have passed, from the pace so far; the
/// settling solve after s = 1 has no known length and is said to be last.
ProgressText progress_text(const LiveProgress& p, double elapsed, int run, int runs);

}  // namespace sutura::ui
