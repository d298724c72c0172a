#pragma once
// Isotropic remeshing of an extracted vessel surface onto its implicit field (the one
// translation unit that includes CGAL, to keep compile time down).
#include <vector>

#include "triangle_soup.hpp"
#include "vessel_field.hpp"

namespace sutura::engine::anatomy {

/// A planar open end of the mesh: every boundary vertex lies in one such plane.
struct EndPlane {
  Vec3 centre;
  Vec3 normal;  ///< unit
};

/// CGAL::Polygon_mesh_processing::isotropic_remeshing (Botsch-Kobbelt: split edges longer
/// than 4/3 L, collapse shorter than 4/5 L, flip towards valence 6, tangential relaxation,
/// projection) with the projection done onto the exact implicit surface: interior vertices by
/// VesselField::project, boundary vertices by VesselField::project_in_plane onto the nearest
/// end plane, so open ends stay planar and the surface stays smooth (not the faceted input).
/// Boundary edges are split/collapsed like the others and their vertices relax along the
/// boundary. Deterministic (CGAL's remesher uses no random numbers; Surface_mesh iterates in
/// index order). Cost O(F * iterations) projections, each O(polyline points).
TriangleMesh isotropic_remesh(const TriangleMesh& input, double target_edge_length, int iterations,
                              const VesselField& field, const std::vector<EndPlane>& ends);

}  // namespace sutura::engine::anatomy
