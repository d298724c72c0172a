#pragma once
// What the suture tool shows before joining: the two chains picked so far (as the join op
// will resolve them), their vertex counts and lengths, and what a count mismatch means.
#include <string>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::ui {

struct SuturePreview {
  std::vector<std::vector<engine::Vec3>> chains;  ///< resolved chains, polylines to draw
  std::vector<std::string> lines;                 ///< text for the panel
};

/// `clicks` in order side A from, A to, B from, B to (any prefix). A chain is resolved once
/// both its ends are clicked, with the rules of the join op (nearest boundary vertex to each
/// point, boundary direction); a click that resolves to nothing is explained in `lines`.
SuturePreview preview_suture(const engine::SurfaceMesh& mesh,
                             const std::vector<engine::Vec3>& clicks);

}  // namespace sutura::ui
