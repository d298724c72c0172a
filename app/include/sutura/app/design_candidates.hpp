#pragma once
// A design_patch op's candidates as sessions of their own, so that a lab sizing many patients
// can run them as a job array on a cluster (docs/patch-design.md) instead of in one process.
//
// A candidate session is the session's header, every action line before the design_patch op
// as written, then the op's parts as plain ops with one width: patch (with `object` and
// `width`), simulate (`objects` defaulting to [object], as design_patch does) and measure
// (with `object`). Replayed, it ends exactly where design_patch's own candidate of that width
// does. Input paths (load's `file` and `landmarks`) are made absolute, so the candidates run
// from any directory. Nothing is simulated to write them.
#include <filesystem>
#include <string>
#include <vector>

#include "sutura/app/session.hpp"

namespace sutura::app {

struct DesignCandidate {
  int line = 0;        ///< the design_patch op's line in the session
  double width = 0.0;  ///< mm
  std::filesystem::path file;
};

/// For each design_patch op of `session`, `count` widths evenly spaced over its width_range
/// (both ends included), each written atomically to `dir` as
/// `<session stem>_line<L>_<k>.jsonl` (k = 1 ... count, narrowest first), plus
/// `<session stem>_candidates.json` listing them (line, width_mm, file). `dir` is created.
/// Throws std::invalid_argument for count outside [2, 1000], a session without a design_patch
/// op, or a file that exists already (candidates are never overwritten: they may be results
/// someone is running). Cost: O(lines x candidates) text.
std::vector<DesignCandidate> emit_design_candidates(const Session& session, const std::filesystem::path& dir,
                                                    int count);

}  // namespace sutura::app
