#include "sutura/engine/measure/hausdorff.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <system_error>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "../run_pair.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, CGAL::AABB_face_graph_triangle_primitive<Mesh>>>;

Mesh to_cgal(const SurfaceMesh& m) {
  Mesh out;
  for (const Vec3& p : m.positions()) out.add_vertex(Point(p.x(), p.y(), p.z()));
  for (const FaceIndices& f : m.faces())
    out.add_face(Mesh::Vertex_index(f[0]), Mesh::Vertex_index(f[1]), Mesh::Vertex_index(f[2]));
  return out;
}

// Subdivisions per face edge so that grid samples are at most `spacing` apart.
int divisions(const SurfaceMesh& m, FaceId f, double spacing) {
  const auto v = m.face_vertices(f);
  double longest = 0.0;
  for (int k = 0; k < 3; ++k)
    longest = std::max(longest, (m.position(v[(k + 1) % 3]) - m.position(v[k])).norm());
  return std::max(1, static_cast<int>(std::ceil(longest / spacing)));
}

// Largest and mean distance from the samples of `from` to the surface in `tree`.
void one_side(const SurfaceMesh& from, const Tree& tree, double spacing, double& largest,
              Vec3& largest_at, double& mean, std::size_t& count) {
  double sum = 0.0;
  largest = 0.0;
  largest_at = from.positions().front();
  count = 0;
  auto add = [&](const Vec3& p) {
    const Point q(p.x(), p.y(), p.z());
    const double d = std::sqrt(CGAL::to_double(tree.squared_distance(q)));
    if (d > largest) largest = d, largest_at = p;
    sum += d;
    ++count;
  };
  for (const Vec3& p : from.positions()) add(p);
  for (std::size_t f = 0; f < from.num_faces(); ++f) {
    const auto v = from.face_vertices(FaceId(f));
    const Vec3 a = from.position(v[0]), b = from.position(v[1]), c = from.position(v[2]);
    const int n = divisions(from, FaceId(f), spacing);
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        if ((i == 0 && j == 0) || (i == n && j == 0) || (i == 0 && j == n)) continue;  // corners
        add(a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a));
      }
  }
  mean = count > 0 ? sum / double(count) : 0.0;
}

}  // namespace

HausdorffDistance hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b, double spacing) {
  if (a.num_faces() == 0 || b.num_faces() == 0)
    throw InvalidArgument("hausdorff_distance: a surface without faces");
  if (!(spacing > 0.0)) spacing = 0.5 * std::min(a.mean_edge_length(), b.mean_edge_length());
  if (!(std::isfinite(spacing) && spacing > 0.0))
    throw InvalidArgument("hausdorff_distance: spacing must be a length > 0 mm");
  double samples = 0.0;
  for (const SurfaceMesh* m : {&a, &b})
    for (std::size_t f = 0; f < m->num_faces(); ++f) {
      const double n = divisions(*m, FaceId(f), spacing);
      samples += 0.5 * (n + 1) * (n + 2);
    }
  if (samples > 2.0e7)
    throw InvalidArgument("hausdorff_distance: spacing " + std::to_string(spacing) +
                          " mm would take about " + std::to_string(static_cast<long long>(samples)) +
                          " samples (limit 20000000)");
  HausdorffDistance h;
  // Each side (the other surface's tree, then this one's samples) is independent of the other,
  // so with two compute threads they run at once, with results identical to one thread's.
  const auto a_side = [&] {
    const Mesh mb = to_cgal(b);
    Tree tb(faces(mb).first, faces(mb).second, mb);
    tb.accelerate_distance_queries();
    one_side(a, tb, spacing, h.a_to_b, h.a_to_b_at, h.mean_a_to_b, h.samples_a);
  };
  const auto b_side = [&] {
    const Mesh ma = to_cgal(a);
    Tree ta(faces(ma).first, faces(ma).second, ma);
    ta.accelerate_distance_queries();
    one_side(b, ta, spacing, h.b_to_a, h.b_to_a_at, h.mean_b_to_a, h.samples_b);
  };
  detail::run_pair(a_side, b_side);
  h.symmetric = std::max(h.a_to_b, h.b_to_a);
  return h;
}

}  // namespace sutura::engine
