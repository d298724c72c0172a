#pragma once
// Bounds on the work one session may ask for, so that a replay ends in bounded time and
// memory or is refused before it starts, with the limit named (issue 27: a tube at the
// generators' 20-million-face ceiling, 10^7 dynamics steps, 2,000 objects, a patch cut at
// 3 um ran for minutes). Each is overridable on the command line for those who know what the
// machine can do (`sutura replay --max-faces ...`; docs/session-format.md, "Limits").
#include <cstddef>

#include "sutura/app/session.hpp"

namespace sutura::app {

class Workspace;
struct SceneObject;

struct Limits {
  /// Faces of one object: a generated or loaded mesh, an object a patch or an appended part
  /// grows to. The fine arch has 20k; a prepared patient vessel some 100k. (--max-faces)
  std::size_t faces_per_object = 1'000'000;
  /// Faces of all objects together. (--max-faces-in-all)
  std::size_t faces_in_all = 2'000'000;
  /// Objects in the workspace. (--max-objects)
  std::size_t objects = 100;
  /// Steps of one run: dynamics steps, relaxation increments plus settling steps. The
  /// bundled sessions use at most a few hundred. (--max-steps)
  long steps = 100'000;
  /// Memory the undo history may hold, MiB: the oldest states are dropped beyond it (a
  /// state larger than this is not kept at all; `undo` then says so). (--max-undo-mb)
  std::size_t undo_megabytes = 1024;
  /// Pixels of one snapshot, all its views (side by side: two): 8192 x 8192 twice took 22 s
  /// on llvmpipe. (--max-pixels)
  std::size_t pixels = 2 * 8192 * 8192;
};

/// Checks every action of `session` against `limits` before any runs, from what the session
/// says (a generated mesh's face count, a patch's estimated faces from its end points' distance,
/// width and spacing, a run's steps, the objects created). Throws SessionError naming the file,
/// line, op and field, the amount and the limit with its flag. Cost O(actions).
void check_limits(const Session& session, const Limits& limits);

/// Estimated bytes one object holds (meshes, state, rest shape, per-element and per-vertex
/// data): what the undo history pays for each version of an object an op changed. O(1).
std::size_t object_bytes(const SceneObject& object);

}  // namespace sutura::app
