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
  const long whole = std::max(1L, std::lround(seconds));  // rounded once, then split
  char buf[32];
  if (whole < 60) std::snprintf(buf, sizeof buf, "%ld s", whole);
  else std::snprintf(buf, sizeof buf, "%ld min %02ld s", whole / 60, whole % 60);
  return buf;
}

}  // namespace

ProgressText progress_text(const LiveProgress& p, double elapsed, int run, int runs) {
  ProgressText t;
  const bool relaxing = p.s >= 0.0;
  if (relaxing) {
    // s only grows: the part of its range covered so far.
    const double s0 = std::max(0.0, p.s_start), s1 = p.s_end > s0 ? p.s_end : 1.0;
    t.fraction = s1 > s0 ? std::clamp((p.s - s0) / (s1 - s0), 0.0, 1.0) : 1.0;
  } else {
    t.fraction = std::clamp(p.fraction, 0.0, 1.0);
  }
  char bar[160];
  if (p.phase.empty())
    std::snprintf(bar, sizeof bar, "%s", phase_words(p.phase).c_str());
  else if (relaxing)
    std::snprintf(bar, sizeof bar, "%s: s = %.2f (to %.2f)", phase_words(p.phase).c_str(), p.s,
                  p.s_end > 0.0 ? p.s_end : 1.0);
  else
    std::snprintf(bar, sizeof bar, "%s: step %d of %d", phase_words(p.phase).c_str(), p.step, p.steps);
  t.bar = bar;
  if (p.paused) t.bar += "  (paused)";
  t.detail = duration(elapsed) + " so far";
  if (p.phase == "settle") {
    t.detail += "; settling takes as long as the shape needs";
  } else if (t.fraction >= 0.05 && elapsed >= 2.0 && t.fraction < 1.0) {
    t.detail += ", about " + duration(elapsed * (1.0 - t.fraction) / t.fraction) + " left";
    if (relaxing && p.s_end >= 1.0) t.detail += " before settling";
  }
  if (runs > 1) t.detail += " (run " + std::to_string(run) + " of " + std::to_string(runs) + ")";
  return t;
}

}  // namespace sutura::ui
