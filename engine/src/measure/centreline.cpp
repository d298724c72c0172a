// The automatic centreline (a translation unit of the CGAL object library, for the AABB
// tree that gives distances to the wall).
//
// Method. For each open end, the vertices are grouped by their geodesic (edge-path) distance
// from the end's loop into bands two mean edge lengths wide; each edge-connected group of a
// band is a ring around the vessel, and the chain of rings from one end to another, at their
// vertices' means, runs along the lumen. Each such path is smoothed, resampled and moved onto
// the section centroids (recentre). The trunk is the path from the root end to the end
// farthest from it; every other end's path is followed from its end until it meets the tree
// built so far, and joins it there (a branch point on the parent's axis, as a surgeon and
// VMTK place it). Why not CGAL's mean-curvature-flow skeleton: it orders collapses in a
// std::set of Polyhedron_3 handles, i.e. by heap address, so two calls in one process can give
// different trees; here every order is by vertex and group index.
#include "sutura/engine/measure/centreline.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/measure/cross_section.hpp"

namespace sutura::engine {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

// Recentring passes: each moves a point to its section's centroid, with the tangent from the
// previous pass's positions.
constexpr int kRecentrePasses = 3;
// Smoothing of each path before it is resampled: ring means zig-zag about the axis where a
// ring is slanted.
constexpr int kSmoothingIterations = 20;
// At most about this many points per path: on a surface far finer than its vessels need
// (a million faces), the points, each recentred on three sections of O(F), would otherwise
// grow with the resolution.
constexpr double kMaxPathPoints = 256.0;
// Width of the distance bands, in mean edge lengths: at least one and a half, so that a band's
// vertices around a tube are edge-connected.
constexpr double kBandWidth = 2.0;
// A branch's path joins the tree at its first point (from its end) nearer to the tree than
// this fraction of the point's distance to the wall.
constexpr double kJoinFraction = 0.5;

using Adjacency = std::vector<std::vector<std::int32_t>>;

Adjacency vertex_adjacency(const SurfaceMesh& vessel) {
  Adjacency adj(vessel.num_vertices());
  for (const FaceIndices& f : vessel.faces())
    for (int i = 0; i < 3; ++i) {
      adj[static_cast<std::size_t>(f[i])].push_back(f[(i + 1) % 3]);
      adj[static_cast<std::size_t>(f[(i + 1) % 3])].push_back(f[i]);
    }
  for (auto& list : adj) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return adj;
}

// The ring path from the loop `from` to the loop `to`: the means of the band groups (see the
// file comment) on the way, from `from`'s centre to `to`'s. The groups and their links form a
// graph; the path is its breadth-first path (neighbours in group order) from the group of
// `from` to the group of `to`'s nearest vertex. Cost O(V log V).
std::vector<Vec3> ring_path(const SurfaceMesh& vessel, const Adjacency& adj, const std::vector<VertexId>& from,
                            const Vec3& from_centre, const std::vector<VertexId>& to, const Vec3& to_centre,
                            double band) {
  const std::size_t nv = vessel.num_vertices();
  const auto& pos = vessel.positions();
  std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
  using Item = std::pair<double, std::int32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (const VertexId v : from) {
    dist[v.index()] = 0.0;
    queue.push({0.0, static_cast<std::int32_t>(v.index())});
  }
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > dist[static_cast<std::size_t>(u)]) continue;
    for (const std::int32_t w : adj[static_cast<std::size_t>(u)]) {
      const double nd = d + (pos[static_cast<std::size_t>(u)] - pos[static_cast<std::size_t>(w)]).norm();
      if (nd < dist[static_cast<std::size_t>(w)]) {
        dist[static_cast<std::size_t>(w)] = nd;
        queue.push({nd, w});
      }
    }
  }
  std::vector<std::int64_t> level(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    if (!std::isfinite(dist[v])) throw InvalidArgument("centreline: the surface is not connected");
    level[v] = static_cast<std::int64_t>(dist[v] / band);
  }
  // Groups: edge-connected vertices of one band, numbered in vertex order.
  std::vector<std::int32_t> group(nv, -1);
  std::vector<Vec3> means;
  std::vector<std::int32_t> stack;
  for (std::size_t s = 0; s < nv; ++s) {
    if (group[s] >= 0) continue;
    const auto id = static_cast<std::int32_t>(means.size());
    group[s] = id;
    stack.assign(1, static_cast<std::int32_t>(s));
    Vec3 sum = Vec3::Zero();
    std::size_t count = 0;
    while (!stack.empty()) {
      const auto u = static_cast<std::size_t>(stack.back());
      stack.pop_back();
      sum += pos[u];
      ++count;
      for (const std::int32_t w : adj[u])
        if (group[static_cast<std::size_t>(w)] < 0 && level[static_cast<std::size_t>(w)] == level[u]) {
          group[static_cast<std::size_t>(w)] = id;
          stack.push_back(w);
        }
    }
    means.push_back(sum / static_cast<double>(count));
  }
  std::vector<std::vector<std::int32_t>> links(means.size());
  for (std::size_t u = 0; u < nv; ++u)
    for (const std::int32_t w : adj[u])
      if (group[u] != group[static_cast<std::size_t>(w)])
        links[static_cast<std::size_t>(group[u])].push_back(group[static_cast<std::size_t>(w)]);
  for (auto& list : links) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  const std::int32_t start = group[from.front().index()];
  VertexId nearest = to.front();
  for (const VertexId v : to)
    if (dist[v.index()] < dist[nearest.index()]) nearest = v;
  const std::int32_t goal = group[nearest.index()];
  std::vector<std::int32_t> parent(means.size(), -1);
  std::queue<std::int32_t> bfs;
  bfs.push(start);
  parent[static_cast<std::size_t>(start)] = start;
  while (!bfs.empty() && parent[static_cast<std::size_t>(goal)] < 0) {
    const std::int32_t u = bfs.front();
    bfs.pop();
    for (const std::int32_t w : links[static_cast<std::size_t>(u)])
      if (parent[static_cast<std::size_t>(w)] < 0) {
        parent[static_cast<std::size_t>(w)] = u;
        bfs.push(w);
      }
  }
  std::vector<Vec3> path{to_centre};
  for (std::int32_t g = goal; g != start; g = parent[static_cast<std::size_t>(g)]) path.push_back(means[static_cast<std::size_t>(g)]);
  path.push_back(means[static_cast<std::size_t>(start)]);
  path.push_back(from_centre);
  std::reverse(path.begin(), path.end());
  // A loop's centre and its group's mean can coincide: no repeated points.
  path.erase(std::unique(path.begin(), path.end()), path.end());
  return path;
}

// A chain's polyline smoothed (ends fixed) and resampled at equal arc length, about `spacing`
// apart (at least one segment).
std::vector<Vec3> smooth_and_resample(std::vector<Vec3> line, double spacing) {
  for (int it = 0; it < kSmoothingIterations; ++it) {
    std::vector<Vec3> next = line;
    for (std::size_t k = 1; k + 1 < line.size(); ++k) next[k] = 0.5 * line[k] + 0.25 * (line[k - 1] + line[k + 1]);
    line = std::move(next);
  }
  std::vector<double> arc(line.size(), 0.0);
  for (std::size_t k = 1; k < line.size(); ++k) arc[k] = arc[k - 1] + (line[k] - line[k - 1]).norm();
  const double length = arc.back();
  const auto segments = static_cast<std::size_t>(std::max(1.0, std::round(length / spacing)));
  std::vector<Vec3> out{line.front()};
  std::size_t k = 1;
  for (std::size_t i = 1; i < segments; ++i) {
    const double s = length * static_cast<double>(i) / static_cast<double>(segments);
    while (k + 1 < line.size() && arc[k] < s) ++k;
    const double span = arc[k] - arc[k - 1];
    const double t = span > 0.0 ? (s - arc[k - 1]) / span : 0.0;
    out.push_back(line[k - 1] + t * (line[k] - line[k - 1]));
  }
  out.push_back(line.back());
  return out;
}

// Moves each interior point of a chain to the area centroid of the vessel's section
// perpendicular to the chain there: the skeleton is medial only approximately, and a round
// section's centroid is its centre. A section is trusted only where it is a closed loop around
// the point, not much longer than wide (near a junction the plane also cuts the other vessel)
// and its centroid is within the point's distance to the wall.
void recentre(std::vector<Vec3>& line, const SurfaceMesh& wall, const std::function<double(const Vec3&)>& wall_distance) {
  if (line.size() < 3) return;
  const double spacing = (line.back() - line.front()).norm() > 0.0 ? (line[1] - line[0]).norm() : 0.0;
  for (int pass = 0; pass < kRecentrePasses; ++pass) {
    const std::vector<Vec3> before = line;
    for (std::size_t k = 1; k + 1 < line.size(); ++k) {
      const double r = wall_distance(before[k]);
      if (!(r > 0.0)) continue;
      // The tangent across about one radius each side: shorter stencils follow the skeleton's
      // residual wiggle and tilt the plane.
      const auto reach = static_cast<std::size_t>(spacing > 0.0 ? std::max(1.0, std::round(r / spacing)) : 1.0);
      const Vec3 tangent = before[std::min(k + reach, line.size() - 1)] - before[k >= reach ? k - reach : 0];
      if (!(tangent.norm() > 0.0)) continue;
      CrossSectionParams params;
      params.max_radius = 3.0 * r;
      CrossSection section;
      try {
        section = cross_section(wall, Plane{before[k], tangent}, params);
      } catch (const InvalidArgument&) {
        continue;
      }
      if (!section.closed || section.max_diameter > 2.0 * section.min_diameter) continue;
      if ((section.centroid - before[k]).norm() > r) continue;
      line[k] = section.centroid;
    }
  }
}

}  // namespace

CentrelineTree extract_centreline(const SurfaceMesh& vessel, const std::vector<VesselEnd>& given_ends) {
  if (vessel.empty()) throw InvalidArgument("centreline: the surface has no faces");
  const auto loops = vessel.boundary_loops();
  if (loops.size() < 2) throw InvalidArgument("centreline: the surface needs at least two open ends (open its caps first)");
  const auto loop_centre = [&](const std::vector<VertexId>& loop) {
    Vec3 c = Vec3::Zero();
    for (const VertexId v : loop) c += vessel.position(v);
    return Vec3(c / static_cast<double>(loop.size()));
  };
  // Ends: as given (each matched to the loop with the nearest centre), or one per loop with
  // the longest loop first (the root: a vessel's inflow is its widest end, as the aortic root).
  // The root matters: a branch's path joins the tree where it meets the trunk on its way to
  // the root, and with a narrow branch as the root the other branches meet the trunk only
  // inside that branch.
  std::vector<Vec3> centres;
  std::vector<std::size_t> loop_of;
  if (given_ends.empty()) {
    const auto perimeter = [&](const std::vector<VertexId>& loop) {
      double l = 0.0;
      for (std::size_t i = 0; i < loop.size(); ++i)
        l += (vessel.position(loop[(i + 1) % loop.size()]) - vessel.position(loop[i])).norm();
      return l;
    };
    std::size_t root = 0;
    for (std::size_t i = 1; i < loops.size(); ++i)
      if (perimeter(loops[i]) > perimeter(loops[root])) root = i;
    loop_of.push_back(root);
    for (std::size_t i = 0; i < loops.size(); ++i)
      if (i != root) loop_of.push_back(i);
    for (const std::size_t i : loop_of) centres.push_back(loop_centre(loops[i]));
  } else {
    if (given_ends.size() != loops.size())
      throw InvalidArgument("centreline: " + std::to_string(given_ends.size()) + " ends given for a surface with " +
                            std::to_string(loops.size()) + " open ends");
    for (const VesselEnd& end : given_ends) {
      std::size_t best = 0;
      for (std::size_t i = 1; i < loops.size(); ++i)
        if ((loop_centre(loops[i]) - end.centre).norm() < (loop_centre(loops[best]) - end.centre).norm()) best = i;
      if (std::find(loop_of.begin(), loop_of.end(), best) != loop_of.end())
        throw InvalidArgument("centreline: ends '" + end.name + "' and another are nearest the same open end");
      centres.push_back(end.centre);
      loop_of.push_back(best);
    }
  }
  const Adjacency adj = vertex_adjacency(vessel);
  double mean_edge = 0.0;
  for (const FaceIndices& f : vessel.faces())
    for (int i = 0; i < 3; ++i) mean_edge += (vessel.positions()[f[i]] - vessel.positions()[f[(i + 1) % 3]]).norm();
  mean_edge /= 3.0 * static_cast<double>(vessel.num_faces());
  const double band = kBandWidth * mean_edge;

  // The open vessel's wall, for distances.
  Mesh wall;
  for (const Vec3& p : vessel.positions()) wall.add_vertex(Point(p.x(), p.y(), p.z()));
  for (const FaceIndices& f : vessel.faces())
    wall.add_face(Mesh::Vertex_index(f[0]), Mesh::Vertex_index(f[1]), Mesh::Vertex_index(f[2]));
  Tree aabb(faces(wall).first, faces(wall).second, wall);
  aabb.accelerate_distance_queries();
  const auto wall_distance = [&](const Vec3& p) { return std::sqrt(aabb.squared_distance(Point(p.x(), p.y(), p.z()))); };
  const auto centred_path = [&](std::size_t a, std::size_t b) {
    std::vector<Vec3> line = ring_path(vessel, adj, loops[loop_of[a]], centres[a], loops[loop_of[b]], centres[b], band);
    double length = 0.0;
    for (std::size_t k = 1; k < line.size(); ++k) length += (line[k] - line[k - 1]).norm();
    line = smooth_and_resample(std::move(line), std::max(mean_edge, length / kMaxPathPoints));
    recentre(line, vessel, wall_distance);
    return line;
  };

  CentrelineTree tree;
  tree.end_nodes.assign(centres.size(), -1);
  const auto add_point = [&](const Vec3& p) {
    tree.points.push_back(p);
    return static_cast<int>(tree.points.size()) - 1;
  };
  // The trunk: from the root (the first end) to the end whose loop is farthest from it along
  // the surface (the largest ring path).
  std::size_t far = 1;
  std::vector<std::vector<Vec3>> to_root(centres.size());
  for (std::size_t e = 1; e < centres.size(); ++e) {
    to_root[e] = centred_path(e, 0);
    if (to_root[e].size() > to_root[far].size()) far = e;
  }
  {
    const std::vector<Vec3>& line = to_root[far];
    int prev = add_point(line.front());
    tree.end_nodes[far] = prev;
    for (std::size_t k = 1; k < line.size(); ++k) {
      const int node = add_point(line[k]);
      tree.edges.emplace_back(prev, node);
      prev = node;
    }
    tree.end_nodes[0] = prev;
  }
  // Every other end, in order: its path until it comes near the tree, then joined to the
  // nearest point of the tree (a new node where that falls inside an edge).
  for (std::size_t e = 1; e < centres.size(); ++e) {
    if (e == far) continue;
    const std::vector<Vec3>& line = to_root[e];
    int prev = add_point(line.front());
    tree.end_nodes[e] = prev;
    for (std::size_t k = 1; k < line.size(); ++k) {
      // The nearest point of the tree.
      double best = std::numeric_limits<double>::infinity();
      std::size_t best_edge = 0;
      double best_t = 0.0;
      for (std::size_t i = 0; i < tree.edges.size(); ++i) {
        const auto [a, b] = tree.edges[i];
        if (a >= tree.end_nodes[e] || b >= tree.end_nodes[e]) continue;  // not this branch's own points
        const Vec3 d = tree.points[b] - tree.points[a];
        const double t = d.squaredNorm() > 0.0 ? std::clamp((line[k] - tree.points[a]).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
        const double dist = (line[k] - (tree.points[a] + t * d)).norm();
        if (dist < best) best = dist, best_edge = i, best_t = t;
      }
      if (best < kJoinFraction * wall_distance(line[k]) || k + 1 == line.size()) {
        const auto [a, b] = tree.edges[best_edge];
        int join = best_t <= 0.0 ? a : best_t >= 1.0 ? b : -1;
        if (join < 0) {
          join = add_point(tree.points[a] + best_t * (tree.points[b] - tree.points[a]));
          tree.edges[best_edge] = {a, join};
          tree.edges.emplace_back(join, b);
        }
        tree.edges.emplace_back(prev, join);
        break;
      }
      const int node = add_point(line[k]);
      tree.edges.emplace_back(prev, node);
      prev = node;
    }
  }
  for (auto& [a, b] : tree.edges)
    if (a > b) std::swap(a, b);
  std::sort(tree.edges.begin(), tree.edges.end());
  std::vector<int> degree(tree.points.size(), 0);
  for (const auto& [a, b] : tree.edges) ++degree[static_cast<std::size_t>(a)], ++degree[static_cast<std::size_t>(b)];
  for (std::size_t v = 0; v < degree.size(); ++v)
    if (degree[v] >= 3) tree.branch_points.push_back(static_cast<int>(v));
  for (const Vec3& p : tree.points) tree.radii.push_back(wall_distance(p));
  return tree;
}

int nearest_centreline_point(const CentrelineTree& tree, const Vec3& p) {
  int best = 0;
  for (int v = 1; v < static_cast<int>(tree.points.size()); ++v)
    if ((tree.points[v] - p).norm() < (tree.points[best] - p).norm()) best = v;
  return best;
}

std::vector<Vec3> centreline_path(const CentrelineTree& tree, const Vec3& from, const Vec3& to) {
  const int a = nearest_centreline_point(tree, from), b = nearest_centreline_point(tree, to);
  if (a == b) throw InvalidArgument("centreline: 'from' and 'to' are nearest the same centreline point");
  // Dijkstra by length from a (in a tree, the one path).
  std::vector<std::vector<std::pair<int, double>>> adj(tree.points.size());
  for (const auto& [u, v] : tree.edges) {
    const double l = (tree.points[u] - tree.points[v]).norm();
    adj[u].emplace_back(v, l);
    adj[v].emplace_back(u, l);
  }
  std::vector<double> dist(tree.points.size(), std::numeric_limits<double>::infinity());
  std::vector<int> parent(tree.points.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[a] = 0.0;
  queue.push({0.0, a});
  while (!queue.empty()) {
    const auto [d, u] = queue.top();
    queue.pop();
    if (d > dist[u]) continue;
    for (const auto& [v, l] : adj[u])
      if (d + l < dist[v]) {
        dist[v] = d + l;
        parent[v] = u;
        queue.push({dist[v], v});
      }
  }
  if (parent[b] < 0) throw InvalidArgument("centreline: 'from' and 'to' lie on unconnected parts");
  std::vector<Vec3> path;
  for (int v = b; v >= 0; v = parent[v]) path.push_back(tree.points[v]);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace sutura::engine
