#pragma once
// report.json: what a replay did, how long each action took, what it wrote, and a summary
// (counts, area, bounds, position hash) of every object.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "sutura/app/workspace.hpp"
#include "sutura/engine/measure/hausdorff.hpp"
#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::app {

/// FNV-1a 64-bit hash of the raw bytes of every vertex position, in vertex order, as 16 hex
/// digits. Equal hashes mean bit-identical positions: the determinism check of replays.
std::string position_hash(const engine::SurfaceMesh& mesh);

/// Counts, boundary loops, area, bounds and position hash of one object.
nlohmann::json object_summary(const SceneObject& object);

/// Face count, smallest angle, 5th-percentile smallest angle (degrees) and edge-length range
/// (mm) of a set of faces (engine::mesh_quality); with `mesh`, also the worst face's index
/// and the centroid of its current shape (mm), to find it.
nlohmann::json mesh_quality_json(const engine::MeshQuality& q, const engine::SurfaceMesh* mesh = nullptr);

/// The one-sided, symmetric and mean distances (mm) and sample counts.
nlohmann::json hausdorff_json(const engine::HausdorffDistance& h);

}  // namespace sutura::app
