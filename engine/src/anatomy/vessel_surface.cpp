#include "vessel_surface.hpp"

#include <algorithm>
#include <cmath>

#include "isotropic_remesh.hpp"
#include "marching_tetrahedra.hpp"
#include "plane_clip.hpp"

namespace sutura::engine::anatomy {

SurfaceMesh vessel_surface(const VesselField& field, const std::vector<VesselEnd>& ends,
                           double extension, double target_edge_length) {
  const double h = std::min(0.35, 0.5 * target_edge_length);
  const Eigen::AlignedBox3d box = field.bounds();
  const Vec3 origin = box.min().array() - 2.0 * h;
  std::array<int, 3> n{};
  for (int d = 0; d < 3; ++d) n[d] = static_cast<int>(std::ceil(box.sizes()[d] / h)) + 5;
  TriangleMesh mesh = marching_tetrahedra(field.sample(origin, h, n), origin, h, n);

  std::vector<EndPlane> planes;
  for (const VesselEnd& e : ends) {
    // The tube beyond the plane: the extension plus its rounded tip (radius r), widened by
    // at most blend / 4 where a junction is near; the grid adds up to h of slack.
    clip_end(mesh, e.centre, e.normal, 1.5 * e.radius + field.blend() + 2.0 * h,
             extension + e.radius + 2.0 * h);
    planes.push_back({e.centre, e.normal});
  }
  mesh = isotropic_remesh(mesh, target_edge_length, 12, field, planes);
  return SurfaceMesh(std::move(mesh.positions), std::move(mesh.faces));
}

}  // namespace sutura::engine::anatomy
