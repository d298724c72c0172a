#include "progress_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sutura::ui {

namespace {

std::string phase_words(const std::string& phase) {
  if (phase == "relax") return "Relaxing the rest shape";
  if (phase == "settle") return "Settling to equilibrium (last step)";
  if (phase == "escape") return "Pushing off an unstable shape";
  if (phase == "retry") return "An increment failed: retrying with half the step";
  if (phase == "simulate") return "Simulating";
  return phase.empty() ? "Starting (assembling and factorising the first tangent)" : phase;
}

std::string duration(double seconds) {
  char buf[32];
  if (seconds < 60.0) std::snprintf(buf, sizeof buf, "%.0f s", std::max(1.0, std::round(seconds)));
  else std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(seconds / 60.0), std::fmod(std::round(seconds), 60.0));
  return buf;
}

}  // namespace

ProgressText progress_text(const LiveProgress& p, double elapsed, std::optional<double> s_at_start, int run,
                           int runs) {
  ProgressText t;
  const bool relaxing = p.s >= 0.0;
  if (relaxing) {
    // s only grows; the part of [s at the start, 1] covered so far.
    const double s0 = s_at_start.value_or(p.s);
    t.fraction = s0 < 1.0 ? std::clamp((p.s - s0) / (1.0 - s0), 0.0, 1.0) : 1.0;
  } else {
    t.fraction = std::clamp(p.fraction, 0.0, 1.0);
  }
  char bar[160];
  if (p.phase.empty())
    std::snprintf(bar, sizeof bar, "%s", phase_words(p.phase).c_str());
  else if (relaxing)
    std::snprintf(bar, sizeof bar, "%s: s = %.2f of 1", phase_words(p.phase).c_str(), p.s);
  else
    std::snprintf(bar, sizeof bar, "%s: step %d of %d", phase_words(p.phase).c_str(), p.step, p.steps);
  t.bar = bar;
  if (p.paused) t.bar += "  (paused)";
  t.detail = duration(elapsed) + " so far";
  if (p.phase == "settle") {
    t.detail += "; settling takes as long as the shape needs";
  } else if (t.fraction >= 0.05 && elapsed >= 2.0 && t.fraction < 1.0) {
    t.detail += ", about " + duration(elapsed * (1.0 - t.fraction) / t.fraction) + " left";
    if (relaxing) t.detail += " before settling";
  }
  if (runs > 1) t.detail += " (run " + std::to_string(run) + " of " + std::to_string(runs) + ")";
  return t;
}

}  // namespace sutura::ui
