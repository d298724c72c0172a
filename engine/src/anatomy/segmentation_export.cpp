#include "sutura/engine/anatomy/segmentation_export.hpp"

#include <cmath>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Uniform in [-1, 1], from 53 random bits.
double uniform_pm1(std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t bits = splitmix64(splitmix64(seed) ^ index) >> 11;
  return 2.0 * static_cast<double>(bits) / 9007199254740992.0 - 1.0;
}

// Each face into four at its edge midpoints.
SurfaceMesh subdivide(const SurfaceMesh& mesh) {
  std::vector<Vec3> x = mesh.positions();
  std::vector<int> midpoint(mesh.num_halfedges(), -1);
  for (const HalfedgeId e : mesh.edges()) {
    const int m = static_cast<int>(x.size());
    x.push_back(0.5 * (mesh.position(mesh.from_vertex(e)) + mesh.position(mesh.to_vertex(e))));
    midpoint[e.index()] = m;
    if (!mesh.is_boundary(e)) midpoint[mesh.twin(e).index()] = m;
  }
  std::vector<FaceIndices> faces;
  faces.reserve(4 * mesh.num_faces());
  for (std::size_t f = 0; f < mesh.num_faces(); ++f) {
    const FaceIndices& t = mesh.faces()[f];
    const FaceId face(static_cast<int>(f));
    const int m01 = midpoint[SurfaceMesh::halfedge(face, 0).index()];
    const int m12 = midpoint[SurfaceMesh::halfedge(face, 1).index()];
    const int m20 = midpoint[SurfaceMesh::halfedge(face, 2).index()];
    faces.push_back({t[0], m01, m20});
    faces.push_back({m01, t[1], m12});
    faces.push_back({m20, m12, t[2]});
    faces.push_back({m01, m12, m20});
  }
  return SurfaceMesh(std::move(x), std::move(faces));
}

}  // namespace

SurfaceMesh segmentation_like(const SurfaceMesh& open_vessel, const SegmentationLikeParams& p) {
  if (!(p.max_edge_length > 0.0 && std::isfinite(p.max_edge_length)))
    throw InvalidArgument("segmentation export: the edge length must be positive");
  if (!(p.noise >= 0.0 && std::isfinite(p.noise)))
    throw InvalidArgument("segmentation export: the noise must be zero or positive");
  if (open_vessel.empty()) throw InvalidArgument("segmentation export: the vessel has no faces");
  // Caps: a fan from each loop's centroid, against the boundary's direction.
  std::vector<Vec3> x = open_vessel.positions();
  std::vector<FaceIndices> faces = open_vessel.faces();
  for (const auto& loop : open_vessel.boundary_loops()) {
    Vec3 c = Vec3::Zero();
    for (const VertexId v : loop) c += open_vessel.position(v);
    const int centre = static_cast<int>(x.size());
    x.push_back(c / static_cast<double>(loop.size()));
    for (std::size_t i = 0; i < loop.size(); ++i)
      faces.push_back({loop[(i + 1) % loop.size()].value, loop[i].value, centre});
  }
  SurfaceMesh mesh(std::move(x), std::move(faces));
  while (mesh.mean_edge_length() > p.max_edge_length) {
    if (4 * mesh.num_faces() > p.max_faces)
      throw InvalidArgument("segmentation export: an edge length of " +
                            std::to_string(p.max_edge_length) + " mm would give more than " +
                            std::to_string(p.max_faces) + " faces");
    mesh = subdivide(mesh);
  }
  if (p.noise > 0.0) {
    const std::vector<Vec3> normals = mesh.vertex_normals();
    std::vector<Vec3> noisy = mesh.positions();
    for (std::size_t v = 0; v < noisy.size(); ++v)
      noisy[v] += p.noise * uniform_pm1(p.seed, v) * normals[v];
    mesh.set_positions(std::move(noisy));
  }
  return mesh;
}

}  // namespace sutura::engine
