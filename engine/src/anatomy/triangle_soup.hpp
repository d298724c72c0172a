#pragma once
// Flat indexed triangle mesh passed between the stages of the anatomy pipeline
// (extraction -> clipping -> remeshing) before it becomes a SurfaceMesh.
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine::anatomy {

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<FaceIndices> faces;
};

}  // namespace sutura::engine::anatomy
