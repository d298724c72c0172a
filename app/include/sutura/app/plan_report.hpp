#pragma once
// The plan report: one self-contained HTML file and a PDF of the same content, handed over with
// a plan (docs/patch-design.md#plan-report). One place for the `plan_report` op, which
// `sutura report SESSION` appends to a replay and the planning window records.
//
// Sections, in order, each an HTML <section> with this id:
//   reproduce     the session file (path, SHA-256, size) and the program (version, commit,
//                 threads), with the command that replays it;
//   plan          the steps in effect, in words, with their lines and notes;
//   views         before | after of every object from three standard views of the workspace
//                 frame (+x left, +y posterior, +z superior: anterior, left lateral,
//                 posterior), sutures and incisions marked;
//   lumen         each lumen profile (a measure along a centreline): area against arc length,
//                 before and after;
//   measurements  every measurement with before, after and change; every check; what
//                 "before" is (loaded or not) for each object;
//   equilibrium   each solve, simulate, unload and design_patch in effect: converged,
//                 residual, stability;
//   design        each design_patch: the target, the choice and why, every candidate;
//   template      each sewn-in patch's cutting template (the HTML: inline SVG at 1:1; the
//                 PDF: a page of its own at 1:1, after the report);
//   materials     every material in use, with the session line that set it and its note.
// A section with nothing to show says so. The HTML is polyglot (well-formed XML as well as
// HTML5); pictures are PNG data URIs, so the file stands alone. The PDF is A4 portrait, drawn
// by render::to_pdf (Helvetica, deflated pictures), every page numbered.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "sutura/app/plan.hpp"
#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"
#include "sutura/render/image.hpp"

namespace sutura::app {

/// What a plan report is made from: the state of a run after its last action.
struct PlanReportSource {
  std::filesystem::path session_file;
  std::string description;
  std::string session_sha256;      ///< 64 hex digits of the session file's bytes
  std::uintmax_t session_bytes = 0;
  std::string program;             ///< e.g. "sutura 0.1.0 (commit 0123abcd4567)"
  int openmp_threads = 0, blas_threads = 0;
  const Plan* plan = nullptr;               ///< required
  const nlohmann::json* measurements = nullptr;  ///< report.json's "measurements"; required
  const nlohmann::json* checks = nullptr;        ///< report.json's "checks"; required
  const Workspace* workspace = nullptr;          ///< required
};

struct PlanReport {
  std::string html;
  std::string pdf;
  /// What report.json lists for the op: sections, pages, pictures, templates.
  nlohmann::json summary;
};

/// Draws one snapshot (the op's objects, side by side before | after); SnapshotRenderer in a run.
using SnapshotDrawer = std::function<render::Image(const SnapshotOp&)>;

/// The report of `source`. `view_width` x `view_height` pixels per half of each standard view
/// (each in [200, 2000]). Throws std::invalid_argument for a missing input or a view size out of
/// range, and passes on the drawer's and the template's errors. Cost: three snapshots of every
/// object, one chart per lumen profile, O(size of the plan and the meshes) otherwise.
PlanReport make_plan_report(const PlanReportSource& source, const SnapshotDrawer& draw, int view_width,
                            int view_height);

/// SHA-256 (nettle) of a file's bytes as 64 lowercase hex digits, and the byte count; throws
/// std::runtime_error naming the file when it cannot be read. Reads it in 64 KiB blocks.
std::pair<std::string, std::uintmax_t> file_sha256(const std::filesystem::path& file);

/// "sutura <version> (commit <12 hex digits>[+changes])" of this build; "(commit unknown)"
/// outside a git checkout. The commit is read at build time (scripts/build_id.cmake).
std::string program_version();

}  // namespace sutura::app
