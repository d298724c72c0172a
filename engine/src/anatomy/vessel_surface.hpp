#pragma once
// Surface of one vessel object: implicit field -> marching tetrahedra -> cut ends -> remesh.
#include <vector>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "vessel_field.hpp"

namespace sutura::engine::anatomy {

/// Meshes the zero set of `field` with near-equilateral triangles of `target_edge_length` mm,
/// open at each of `ends` (the implicit tubes must run straight through each end plane for at
/// least `extension` mm before their rounded tips). The field is sampled on a grid of spacing
/// min(0.35, L/2) mm, so topology is resolved for lumens down to about 1 mm radius. Throws
/// TopologyError if the result is not a valid manifold (a layout the pipeline cannot mesh).
/// Cost: O(grid nodes) sampling plus 12 remeshing iterations.
SurfaceMesh vessel_surface(const VesselField& field, const std::vector<VesselEnd>& ends,
                           double extension, double target_edge_length);

}  // namespace sutura::engine::anatomy
