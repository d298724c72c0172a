#pragma once
// report.json: what a replay did, how long each action took, what it wrote, and a summary
// (counts, area, bounds, position hash) of every object.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "sutura/app/workspace.hpp"

namespace sutura::app {

/// FNV-1a 64-bit hash of the raw bytes of every vertex position, in vertex order, as 16 hex
/// digits. Equal hashes mean bit-identical positions: the determinism check of replays.
std::string position_hash(const engine::SurfaceMesh& mesh);

/// Counts, boundary loops, area, bounds and position hash of one object.
nlohmann::json object_summary(const SceneObject& object);

}  // namespace sutura::app
