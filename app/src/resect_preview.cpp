#include "sutura/app/resect_preview.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/measure/cross_section.hpp"

namespace sutura::app {

namespace {

// Unit tangent of the tree at point i: along its edge, or at a branch point along the pair of
// edges that runs most nearly straight through it.
engine::Vec3 tangent(const engine::CentrelineTree& tree, const std::vector<std::vector<int>>& next, std::size_t i) {
  const engine::Vec3& p = tree.points[i];
  const auto& n = next[i];
  if (n.size() == 1) return (tree.points[std::size_t(n[0])] - p).normalized();
  engine::Vec3 t = engine::Vec3::UnitZ();
  double straightest = 2.0;
  for (std::size_t a = 0; a < n.size(); ++a)
    for (std::size_t b = a + 1; b < n.size(); ++b) {
      const engine::Vec3 u = (tree.points[std::size_t(n[a])] - p).normalized();
      const engine::Vec3 v = (tree.points[std::size_t(n[b])] - p).normalized();
      if (u.dot(v) < straightest) straightest = u.dot(v), t = v - u;
    }
  return t.normalized();
}

}  // namespace

engine::CentrelineTree tool_centreline(const engine::SurfaceMesh& mesh) {
  return engine::extract_centreline(mesh);
}

SectionCut cut_at(const engine::SurfaceMesh& mesh, const engine::CentrelineTree& tree, const engine::Vec3& click) {
  std::vector<std::vector<int>> next(tree.points.size());
  for (const auto& [a, b] : tree.edges) {
    next[std::size_t(a)].push_back(b);
    next[std::size_t(b)].push_back(a);
  }
  // The point whose section the click lies on: off it along the tangent by the least, and at
  // the inscribed radius across it. The plain nearest point can be on a branch's path where
  // it joins the trunk, off the axis of the vessel clicked.
  std::size_t best = 0;
  engine::Vec3 best_t = engine::Vec3::UnitZ();
  double best_score = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < tree.points.size(); ++k) {
    if (next[k].empty()) continue;
    const engine::Vec3 t = tangent(tree, next, k);
    const engine::Vec3 d = click - tree.points[k];
    const double axial = d.dot(t);
    const double score = std::abs(axial) + std::abs((d - axial * t).norm() - tree.radii[k]);
    if (score < best_score) best_score = score, best = k, best_t = t;
  }
  if (!(best_score < std::numeric_limits<double>::infinity()))
    throw engine::InvalidArgument("the vessel's centreline has no segment to cut across");
  // The lumen outline in that plane, within a few radii of the click's distance from the
  // point (a severe narrowing can put the centreline near the wall): its centroid is the cut's
  // centre, the farthest outline point from it the reach the cut needs.
  engine::CrossSectionParams within;
  within.max_radius = 3.0 * std::max((click - tree.points[best]).norm(), tree.radii[best]);
  SectionCut cut;
  const engine::CrossSection section = engine::cross_section(mesh, {tree.points[best], best_t}, within);
  cut.plane = {section.centroid, best_t};
  for (const auto& q : section.points) cut.wall_distance = std::max(cut.wall_distance, (q - section.centroid).norm());
  cut.diameter = section.equivalent_diameter;
  cut.closed = section.closed;
  return cut;
}

ResectPreview preview_resection(const engine::SurfaceMesh& mesh, const engine::CentrelineTree& tree,
                                const std::vector<engine::Vec3>& clicks, double reach) {
  ResectPreview out;
  double widest = 0.0;
  try {
    for (std::size_t k = 0; k < std::min<std::size_t>(clicks.size(), 2); ++k) {
      out.cuts.push_back(cut_at(mesh, tree, clicks[k]));
      out.planes.push_back(out.cuts.back().plane);
      widest = std::max(widest, out.cuts.back().wall_distance);
    }
  } catch (const std::exception& e) {
    out.error = std::string("no cut across the vessel there: ") + e.what();
    return out;
  }
  out.reach = reach > 0.0 ? reach : ResectPreview::kAutoReach * widest;
  for (std::size_t k = 0; k < out.cuts.size(); ++k)
    if (!out.cuts[k].closed) {
      out.error = "cut " + std::to_string(k + 1) + " does not go all the way round the vessel: click where "
                  "the wall is whole";
      return out;
    }
  if (out.planes.size() < 2) return out;
  if ((out.planes[0].origin - out.planes[1].origin).norm() == 0.0) {
    out.error = "both clicks place the plane at the same point of the centreline: click farther apart";
    return out;
  }
  engine::ResectionParams params;
  params.radius = out.reach;
  try {
    const engine::ResectionResult r =
        engine::resect(mesh, out.planes, 0.5 * (out.planes[0].origin + out.planes[1].origin), params);
    for (const auto& loop : r.loops) {
      std::vector<engine::Vec3> pts;
      for (const auto v : loop.vertices) pts.push_back(r.mesh.position(v));
      out.loops.push_back(std::move(pts));
    }
    std::vector<bool> kept(mesh.num_faces(), false);
    for (const auto& o : r.maps.faces)
      if (o.parent.valid() && o.parent.index() < kept.size()) kept[o.parent.index()] = true;
    for (std::size_t f = 0; f < kept.size(); ++f) {
      if (kept[f]) continue;
      const auto v = mesh.face_vertices(engine::FaceId(int(f)));
      out.removed.push_back((mesh.position(v[0]) + mesh.position(v[1]) + mesh.position(v[2])) / 3.0);
    }
    out.removed_faces = r.removed_faces;
    out.removed_area = r.removed_area;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace sutura::app
