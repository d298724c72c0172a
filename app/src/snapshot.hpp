#pragma once
// Snapshot rendering for replays: turns workspace objects into the renderer's plain arrays.
#include <memory>

#include "sutura/app/session.hpp"
#include "sutura/app/workspace.hpp"
#include "sutura/render/image.hpp"
#include "sutura/render/renderer.hpp"

namespace sutura::app {

/// Owns the off-screen GL context, created on the first snapshot (a replay without snapshots
/// never touches OpenGL) and reused for every later one.
class SnapshotRenderer {
 public:
  /// Renders the op's objects (before | after when side_by_side). Throws std::runtime_error
  /// for an unknown object name or a field the objects cannot provide, render::GlError on
  /// GL failure.
  render::Image render(const SnapshotOp& op, const Workspace& workspace);

 private:
  std::unique_ptr<render::GlContext> context_;
  std::unique_ptr<render::Renderer> renderer_;
};

}  // namespace sutura::app
