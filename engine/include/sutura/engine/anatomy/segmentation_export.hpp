#pragma once
// A synthetic segmentation export: what 3D Slicer, Mimics or ITK-SNAP would hand a surgeon for
// a generated vessel. The test input of `sutura prepare` (docs/patient-data.md), so that no test
// depends on a file that cannot be regenerated.
#include <cstdint>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct SegmentationLikeParams {
  /// Faces are split into four (edge midpoints) until the mean edge is at most this, mm.
  double max_edge_length = 0.3;
  /// Every vertex moves along its normal by a uniform random amount in [-noise, noise], mm.
  double noise = 0.02;
  std::uint64_t seed = 1;  ///< of the noise (SplitMix64 of seed and vertex index)
  std::size_t max_faces = 20'000'000;  ///< refused beyond this
};

/// Closes every open end of `open_vessel` with a flat cap (a fan around the loop's centroid,
/// oriented like the wall), subdivides, and adds noise. The result is closed, consistently
/// oriented and deterministic. Throws InvalidArgument for a non-positive edge length, a negative
/// or non-finite noise, or a result of more than max_faces faces.
SurfaceMesh segmentation_like(const SurfaceMesh& open_vessel, const SegmentationLikeParams& params);

}  // namespace sutura::engine
