#pragma once
// What a session's solver and surgery ops and load's prepare mean where a field is left out:
// the engine settings of each session format version, every field written out
// (session_defaults.cpp).
//
// Why: the parsers used to start from the engine structs' own member defaults, so a default
// changed in the engine changed what every recorded session meant (it happened to the
// dynamics scheme). A planning record must replay the same way years later, so the values are
// pinned here, per format version, and the engine's defaults may move on. A field added to one
// of these engine structs stops the build (a size check in session_defaults.cpp, and a field
// count for the structs with room in their padding) until it is given its value here, for
// every version, the old versions getting the value that keeps their old behaviour. (Elsewhere
// the check sees a size change only; docs/session-format.md says so.)
//
// keep_going, a runtime hook, is left empty (the replay sets it). energy_reference and
// force_reference are pinned to 0 (no floor on the solver's scales), which is what a session
// means; only a relaxation raises them, inside the engine.
#include "sutura/engine/patient/prepare.hpp"
#include "sutura/engine/sim/area_barrier.hpp"
#include "sutura/engine/sim/contact.hpp"
#include "sutura/engine/sim/dynamics.hpp"
#include "sutura/engine/sim/static_solver.hpp"
#include "sutura/engine/sim/unload.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/patch_plan.hpp"
#include "sutura/engine/surgery/relaxation.hpp"
#include "sutura/engine/surgery/resect.hpp"
#include "sutura/engine/surgery/seam_match.hpp"

namespace sutura::app::detail {

/// `solve`, `unload` and a relaxation's increments. Throws std::invalid_argument for a
/// version this build does not read (below 1 or above kSessionFormatVersion).
engine::StaticSolverParams static_solver_defaults(int version);
/// `simulate` (plain dynamics and a relaxation's dynamics). Throws as above.
engine::DynamicsParams dynamics_defaults(int version);
/// `simulate`'s `relax`, with statics and dynamics from the two functions above. Throws as above.
engine::RelaxationParams relaxation_defaults(int version);
/// `unload`: its fixed-point iteration (the solves' settings are static_solver_defaults).
/// Throws as above.
engine::UnloadParams unload_defaults(int version);
/// `simulate`'s `contact`. Throws as above.
engine::ContactParams contact_defaults(int version);
/// The collapse barrier of `"collapse_barrier": true`. Throws as above.
engine::AreaBarrierParams area_barrier_defaults(int version);
/// The passes of every remesh a surgery op makes: `remesh`'s (its `iterations` field, when
/// given, replaces theirs), the seams' of `join`, `patch` and `resect`, the band's of `resect`;
/// incise's bands as incision_defaults says. Throws as above.
engine::RemeshPasses remesh_passes_defaults(int version);
/// The seam match of `join`, `patch` (its lips) and `resect` (its anastomosis's loops): every
/// field but the target length and the object's constraints (which the replay gives). Throws
/// as above.
engine::ResampleChainsParams seam_defaults(int version);
/// The join of `join`, `patch` and `resect`: every field but the held vertices and the
/// pairing (which the replay gives) and `join`'s placement (which the op gives). Throws as above.
engine::JoinParams join_defaults(int version);
/// `incise`: every field but the constrained vertices and edges (which the replay gives).
/// Throws as above.
engine::IncisionParams incision_defaults(int version);
/// `patch` (and `design_patch`'s patch): every field but the seam resampling counts (which
/// the replay gives); min_edge_length, a fifth of the width since version 2, is set by the
/// parser from the width it reads. Throws as above.
engine::PatchPlanParams patch_plan_defaults(int version);
/// `load`'s `prepare`: every field (the replay sets max_faces from its limits). Throws as above.
engine::PrepareParams prepare_defaults(int version);
/// `resect`. Throws as above.
engine::ResectionParams resection_defaults(int version);

}  // namespace sutura::app::detail
