#include "cgal_remesh.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <memory>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/angle_and_area_smoothing.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/tangential_relaxation.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Constrained_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/Edge_collapse_visitor_base.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "../run_pair.hpp"
#include "sutura/engine/surgery/surface_point.hpp"

namespace sutura::engine::detail {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Segment = Kernel::Segment_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VI = Mesh::Vertex_index;
using HI = Mesh::Halfedge_index;
using FI = Mesh::Face_index;
using EI = Mesh::Edge_index;
namespace PMP = CGAL::Polygon_mesh_processing;

using FacePrimitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using FaceTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, FacePrimitive>>;
using SegmentIt = std::vector<Segment>::const_iterator;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, SegmentIt>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

Vec3 to_vec(const Point& p) { return {p.x(), p.y(), p.z()}; }
Point to_point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

double distance_to_polyline(const Vec3& p, const std::vector<Vec3>& curve) {
  if (curve.size() == 1) return (p - curve[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const Vec3 d = curve[i + 1] - curve[i];
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((p - curve[i]).dot(d) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (curve[i] + t * d)).norm());
  }
  return best;
}

double angle_at(const Point& a, const Point& b, const Point& c) {  // at a, in (b, a, c)
  const Vec3 u = to_vec(b) - to_vec(a), w = to_vec(c) - to_vec(a);
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

double smallest_angle(const Point& a, const Point& b, const Point& c) {
  return std::min({angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
}

// Finishes the band the way CGAL's valence-driven flips do not: an edge inside the band whose
// two opposite angles add up to more than pi is flipped (the Delaunay criterion, which
// maximises the smallest angle of a planar pair), where the pair is nearly flat (within 20
// degrees, so the surface keeps its shape) and the flip makes no duplicate edge. Constrained
// edges are never flipped. Deterministic: sweeps in edge index order, at most 20 sweeps.
template <class EdgeMap, class FaceMap>
void delaunay_flips(Mesh& mesh, const EdgeMap& constrained, const FaceMap& in_region) {
  const double flat = std::cos(20.0 * M_PI / 180.0);
  for (int sweep = 0; sweep < 20; ++sweep) {
    int flips = 0;
    for (EI e : mesh.edges()) {
      if (constrained[e] || mesh.is_border(e)) continue;
      const auto h = mesh.halfedge(e), t = mesh.opposite(h);
      if (!in_region[mesh.face(h)] || !in_region[mesh.face(t)]) continue;
      const VI a = mesh.source(h), b = mesh.target(h);
      const VI c = mesh.target(mesh.next(h)), d = mesh.target(mesh.next(t));
      const Point &pa = mesh.point(a), &pb = mesh.point(b), &pc = mesh.point(c), &pd = mesh.point(d);
      if (angle_at(pc, pa, pb) + angle_at(pd, pa, pb) <= M_PI + 1e-9) continue;
      const Vec3 n1 = (to_vec(pb) - to_vec(pa)).cross(to_vec(pc) - to_vec(pa)).normalized();
      const Vec3 n2 = (to_vec(pa) - to_vec(pb)).cross(to_vec(pd) - to_vec(pb)).normalized();
      if (!(n1.dot(n2) > flat)) continue;
      if (mesh.halfedge(c, d) != Mesh::null_halfedge()) continue;
      // The new pair (c, d, a) and (d, c, b) must keep the orientation of the old one.
      const Vec3 m1 = (to_vec(pd) - to_vec(pc)).cross(to_vec(pa) - to_vec(pc));
      const Vec3 m2 = (to_vec(pc) - to_vec(pd)).cross(to_vec(pb) - to_vec(pd));
      if (!(m1.dot(n1 + n2) > 0.0 && m2.dot(n1 + n2) > 0.0)) continue;
      // ... and be better shaped than the old one (a flat new triangle never is).
      if (std::min(smallest_angle(pc, pd, pa), smallest_angle(pd, pc, pb)) <=
          std::min(smallest_angle(pa, pb, pc), smallest_angle(pb, pa, pd)))
        continue;
      CGAL::Euler::flip_edge(h, mesh);
      ++flips;
    }
    if (flips == 0) break;
  }
}


Vec3 normal_of(const Point& a, const Point& b, const Point& c) {
  return (to_vec(b) - to_vec(a)).cross(to_vec(c) - to_vec(a));
}

// The corners of f with `from` replaced by `to`'s position (the shape f has after a collapse).
std::array<Point, 3> corners_after(const Mesh& mesh, FI f, VI from, const Point& to) {
  std::array<Point, 3> p;
  int k = 0;
  for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) p[k++] = v == from ? to : mesh.point(v);
  return p;
}

// Needles the flips cannot mend: a band face whose smallest angle is below `goal` loses its
// shortest edge by a collapse into one end, where the other end may go (not fixed, not on the
// open boundary, all its faces in the band, on a constrained polyline only along it as one of
// its inner vertices) and the collapse raises the smallest angle around it without folding a
// face or lengthening an edge by more than half. The vertex kept keeps its place and identity;
// the polylines keep every other vertex (their edges are marked again after the collapse).
// Returns the number of collapses. Deterministic: faces in index order.
template <class EdgeMap, class VertexMap, class IdMap, class FaceMap, class OnPolyline>
int collapse_needles(Mesh& mesh, EdgeMap& constrained, VertexMap& fixed, IdMap& old_id,
                     const FaceMap& in_region, const OnPolyline& on_polyline,
                     double goal = 20.0 * M_PI / 180.0) {
  int collapses = 0;
  std::vector<FI> bad;
  for (FI f : mesh.faces()) {
    if (!in_region[f]) continue;
    std::array<Point, 3> p;
    int k = 0;
    for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) p[k++] = mesh.point(v);
    if (smallest_angle(p[0], p[1], p[2]) < goal) bad.push_back(f);
  }
  for (FI f : bad) {
    if (mesh.is_removed(f)) continue;
    // Shortest edge of f.
    auto h = mesh.halfedge(f), best = h;
    double shortest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k, h = mesh.next(h)) {
      const double len = (to_vec(mesh.point(mesh.source(h))) - to_vec(mesh.point(mesh.target(h)))).norm();
      if (len < shortest) shortest = len, best = h;
    }
    const EI e = mesh.edge(best);
    if (mesh.is_border(e) || !CGAL::Euler::does_satisfy_link_condition(e, mesh)) continue;
    double best_gain = 0.0;
    VI gone = Mesh::null_vertex(), kept = Mesh::null_vertex();
    for (const bool flip : {false, true}) {
      const VI r = flip ? mesh.target(best) : mesh.source(best);
      const VI q = flip ? mesh.source(best) : mesh.target(best);
      if (fixed[r] || mesh.is_border(r)) continue;
      if (on_polyline(r)) {  // only along its polyline, where it is an inner vertex
        int along = 0;
        for (auto g : CGAL::halfedges_around_target(mesh.halfedge(r), mesh))
          along += constrained[mesh.edge(g)] ? 1 : 0;
        if (!constrained[e] || along != 2) continue;
      }
      double before = M_PI, after = M_PI, longest_before = 0.0, longest_after = 0.0;
      bool ok = true;
      for (auto g : CGAL::halfedges_around_target(mesh.halfedge(r), mesh)) {
        const FI g_face = mesh.face(g);
        if (g_face == Mesh::null_face() || !in_region[g_face]) {
          ok = false;
          break;
        }
        longest_before = std::max(longest_before, (to_vec(mesh.point(mesh.source(g))) - to_vec(mesh.point(r))).norm());
        const auto old_corners = corners_after(mesh, g_face, Mesh::null_vertex(), Point());
        before = std::min(before, smallest_angle(old_corners[0], old_corners[1], old_corners[2]));
        bool has_q = false;
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(g_face), mesh)) has_q |= v == q;
        if (has_q) continue;  // removed with the edge
        const auto p = corners_after(mesh, g_face, r, mesh.point(q));
        const Vec3 n_old = normal_of(old_corners[0], old_corners[1], old_corners[2]);
        const Vec3 n_new = normal_of(p[0], p[1], p[2]);
        if (!(n_new.dot(n_old) > 0.2 * n_new.norm() * n_old.norm())) {
          ok = false;
          break;
        }
        after = std::min(after, smallest_angle(p[0], p[1], p[2]));
        longest_after = std::max(longest_after, (to_vec(mesh.point(mesh.source(g))) - to_vec(mesh.point(q))).norm());
      }
      if (!ok || longest_after > 1.5 * longest_before || after - before <= best_gain) continue;
      best_gain = after - before;
      gone = r;
      kept = q;
    }
    if (gone == Mesh::null_vertex()) continue;
    const Point keep_at = mesh.point(kept);
    const int keep_id = old_id[kept];
    const bool keep_fixed = fixed[kept];
    // The constrained edges at both ends, by their other vertex: restored on the vertex kept
    // (a collapse merges two edges of each face of e into one, and may keep the unmarked one).
    std::vector<VI> marked;
    for (const VI end : {gone, kept})
      for (auto g : CGAL::halfedges_around_target(mesh.halfedge(end), mesh))
        if (constrained[mesh.edge(g)] && mesh.edge(g) != e) marked.push_back(mesh.source(g));
    const VI v = CGAL::Euler::collapse_edge(e, mesh);
    for (const VI x : marked)
      if (x != gone && x != kept) constrained[mesh.edge(mesh.halfedge(x, v))] = true;
    mesh.point(v) = keep_at;
    old_id[v] = keep_id;
    fixed[v] = keep_fixed;
    ++collapses;
  }
  return collapses;
}

// Band faces still thinner than `goal` after the flips and needle collapses: each of their
// corners that may move (not fixed, not on the open boundary or a polyline, all its faces in
// the band) goes where the smallest angle of its faces is largest, found by a pattern search
// in its tangent plane (eight directions, from a quarter of its mean edge length, halved down
// to a sixty-fourth), each trial point projected onto the input. A move is kept only when it
// raises that smallest angle and turns no face's normal by more than about 78 degrees. Only
// faces around a moved vertex change (a face there may get worse, never below the new
// smallest angle among them, which only rises), so the band's smallest angle never falls. At most 32 trials of eight points per vertex.
// Deterministic: faces in index order, corners in face order. Returns the vertices moved.
template <class VertexMap, class FaceMap, class OnPolyline, class Project>
int raise_smallest_angles(Mesh& mesh, const VertexMap& fixed, const FaceMap& in_region,
                          const OnPolyline& on_polyline, const Project& project, double goal) {
  std::vector<VI> corners;
  for (FI f : mesh.faces()) {
    if (!in_region[f]) continue;
    const auto p = corners_after(mesh, f, Mesh::null_vertex(), Point());
    if (smallest_angle(p[0], p[1], p[2]) >= goal) continue;
    for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) corners.push_back(v);
  }
  int moved = 0;
  for (VI v : corners) {
    if (fixed[v] || mesh.is_border(v) || on_polyline(v)) continue;
    std::vector<FI> ring;
    std::vector<Vec3> normals;
    Vec3 normal = Vec3::Zero();
    double mean_edge = 0.0;
    bool inside = true;
    for (HI g : CGAL::halfedges_around_target(mesh.halfedge(v), mesh)) {
      const FI f = mesh.face(g);
      inside = inside && f != Mesh::null_face() && in_region[f];
      if (!inside) break;
      ring.push_back(f);
      const auto p = corners_after(mesh, f, Mesh::null_vertex(), Point());
      normals.push_back(normal_of(p[0], p[1], p[2]));
      normal += normals.back().normalized();
      mean_edge += (to_vec(mesh.point(mesh.source(g))) - to_vec(mesh.point(v))).norm();
    }
    if (!inside || ring.empty() || !(normal.norm() > 0.0)) continue;
    mean_edge /= double(ring.size());
    normal.normalize();
    // The smallest angle of the ring with v at q; -1 when a face would fold.
    const auto score = [&](const Point& q) {
      double worst = M_PI;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto p = corners_after(mesh, ring[i], v, q);
        const Vec3 n = normal_of(p[0], p[1], p[2]);
        if (!(n.dot(normals[i]) > 0.2 * n.norm() * normals[i].norm())) return -1.0;
        worst = std::min(worst, smallest_angle(p[0], p[1], p[2]));
      }
      return worst;
    };
    const Point start = mesh.point(v);
    const Vec3 u = (std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(normal).normalized();
    const Vec3 w = normal.cross(u);
    Point best = start;
    double best_score = score(start);
    const double start_score = best_score;
    double step = 0.25 * mean_edge;
    for (int trial = 0; trial < 32 && step >= mean_edge / 64.0; ++trial) {
      Point next = best;
      double next_score = best_score;
      for (int k = 0; k < 8; ++k) {
        const double a = k * M_PI / 4.0;
        mesh.point(v) = to_point(to_vec(best) + step * (std::cos(a) * u + std::sin(a) * w));
        const Point q = project(v);
        mesh.point(v) = start;
        const double s = score(q);
        if (s > next_score) next_score = s, next = q;
      }
      if (next_score > best_score) {
        best = next;
        best_score = next_score;
      } else {
        step *= 0.5;
      }
    }
    if (best_score > start_score) {
      mesh.point(v) = best;
      ++moved;
    }
  }
  return moved;
}

// Collapses each marked open-boundary vertex r of the region (not fixed) into one of its two
// boundary neighbours q, which keeps its place: the nearer first, the other if that one would
// fold a face of r (normal turned by more than about 78 degrees) or break the link condition.
// The constrained edges at both ends are marked again on q. Returns the number removed.
// Deterministic: vertices in index order.
template <class EdgeMap, class VertexMap, class IdMap, class FaceMap>
int dissolve_boundary_vertices(Mesh& mesh, EdgeMap& constrained, VertexMap& fixed,
                               IdMap& old_id, const FaceMap& in_region,
                               const std::vector<bool>& marked_input) {
  std::vector<VI> marked;
  for (VI v : mesh.vertices())
    if (v.idx() < marked_input.size() && marked_input[v.idx()] && !fixed[v] && mesh.is_border(v))
      marked.push_back(v);
  int removed = 0;
  for (const VI r : marked) {
    if (mesh.is_removed(r)) continue;
    // Its two boundary neighbours: the border halfedge into r comes from one, out of it goes
    // to the other.
    std::vector<HI> candidates;
    for (auto g : CGAL::halfedges_around_target(mesh.halfedge(r), mesh)) {
      if (mesh.is_border(g)) candidates.push_back(g);                  // q -> r on the border
      if (mesh.is_border(mesh.opposite(g))) candidates.push_back(g);   // q -> r, r -> q border
    }
    if (candidates.size() != 2) continue;  // not a simple boundary vertex
    bool all_in_region = true;
    for (FI f : CGAL::faces_around_target(mesh.halfedge(r), mesh))
      all_in_region = all_in_region && (f == Mesh::null_face() || in_region[f]);
    if (!all_in_region) continue;
    auto length = [&](HI g) {
      return (to_vec(mesh.point(mesh.source(g))) - to_vec(mesh.point(r))).norm();
    };
    if (length(candidates[1]) < length(candidates[0])) std::swap(candidates[0], candidates[1]);
    for (const HI g : candidates) {
      const VI q = mesh.source(g);
      const EI e = mesh.edge(g);
      if (!CGAL::Euler::does_satisfy_link_condition(e, mesh)) continue;
      bool ok = true;
      for (auto a : CGAL::halfedges_around_target(mesh.halfedge(r), mesh)) {
        const FI f = mesh.face(a);
        if (f == Mesh::null_face()) continue;
        bool has_q = false;
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) has_q |= v == q;
        if (has_q) continue;  // removed with the edge
        const auto old_corners = corners_after(mesh, f, Mesh::null_vertex(), Point());
        const auto p = corners_after(mesh, f, r, mesh.point(q));
        const Vec3 n_old = normal_of(old_corners[0], old_corners[1], old_corners[2]);
        const Vec3 n_new = normal_of(p[0], p[1], p[2]);
        ok = ok && n_new.dot(n_old) > 0.2 * n_new.norm() * n_old.norm();
      }
      if (!ok) continue;
      const Point keep_at = mesh.point(q);
      const int keep_id = old_id[q];
      const bool keep_fixed = fixed[q];
      std::vector<VI> ends;
      for (const VI end : {r, q})
        for (auto a : CGAL::halfedges_around_target(mesh.halfedge(end), mesh))
          if (constrained[mesh.edge(a)] && mesh.edge(a) != e) ends.push_back(mesh.source(a));
      const VI v = CGAL::Euler::collapse_edge(e, mesh);
      for (const VI x : ends)
        if (x != r && x != q) constrained[mesh.edge(mesh.halfedge(x, v))] = true;
      mesh.point(v) = keep_at;
      old_id[v] = keep_id;
      fixed[v] = keep_fixed;
      ++removed;
      break;
    }
  }
  return removed;
}

namespace SMS = CGAL::Surface_mesh_simplification;

// During the collapses: when a vertex on a held edge is collapsed into a free one, the vertex
// that stays takes its point (Constrained_placement) and, here, its key and its pin, so that the
// key names the input vertex whose point it holds.
struct FollowPinnedVertex : SMS::Edge_collapse_visitor_base<Mesh> {
  Mesh::Property_map<VI, int> key;
  Mesh::Property_map<VI, bool> pinned;
  void OnCollapsed(const Profile& profile, const VI& kept) {
    const VI gone = kept == profile.v0() ? profile.v1() : profile.v0();
    if (!pinned[gone]) return;
    key[kept] = key[gone];
    pinned[kept] = true;
  }
};

// With `keep_pinned_apart`: refuses a collapse that would join two vertices on held edges by a
// new edge (two halves joined along their cut must not both have an edge between the same two
// cut vertices).
struct KeepPinnedApart {
  Mesh::Property_map<VI, bool> pinned;
  bool active = false;
  template <class Profile>
  boost::optional<Point> operator()(const Profile& profile, const boost::optional<Point>& at) const {
    if (!active || !at) return at;
    const Mesh& m = profile.surface_mesh();
    VI p = profile.v0(), f = profile.v1();
    if (!pinned[p]) std::swap(p, f);
    if (!pinned[p]) return at;
    for (HI h : CGAL::halfedges_around_target(f, m)) {
      const VI n = m.source(h);
      if (n == p || !pinned[n]) continue;
      if (m.halfedge(n, p) == Mesh::null_halfedge()) return boost::none;
    }
    return at;
  }
};

// Shortest edges first, each collapsed to its midpoint, until none is shorter than `below`.
// Held edges never collapse and their vertices neither move nor go (CGAL collapses no edge whose
// two ends are both on held edges).
void collapse_shortest(Mesh& m, Mesh::Property_map<EI, bool> held, Mesh::Property_map<VI, int> key,
                       double below, bool keep_pinned_apart) {
  auto pinned = m.add_property_map<VI, bool>("v:pinned", false).first;
  for (EI e : m.edges())
    if (held[e]) pinned[m.vertex(e, 0)] = pinned[m.vertex(e, 1)] = true;
  const SMS::Edge_length_stop_predicate<double> stop(below);
  const SMS::Constrained_placement<SMS::Midpoint_placement<Mesh>, decltype(held)> placement(held);
  FollowPinnedVertex visitor;
  visitor.key = key;
  visitor.pinned = pinned;
  SMS::edge_collapse(m, stop,
                     CGAL::parameters::get_cost(SMS::Edge_length_cost<Mesh>())
                         .get_placement(placement)
                         .edge_is_constrained_map(held)
                         .visitor(visitor)
                         .filter(KeepPinnedApart{pinned, keep_pinned_apart}));
  m.remove_property_map(pinned);
}

// One half of the mesh being coarsened, as a mesh of its own: the cut between the halves is an
// open boundary of each, held like one.
struct Half {
  Mesh mesh;
  Mesh::Property_map<VI, int> whole;   // the vertex of the whole mesh
  Mesh::Property_map<EI, bool> held;   // constrained in the whole mesh, or on this half's boundary
  Mesh::Property_map<EI, bool> given;  // constrained in the whole mesh
  Mesh::Property_map<FI, int> patch;
};

// Coarsens `mesh` (every face in the region, no vertex fixed) by collapse_shortest. A mesh of
// `in_halves_from` faces or more is cut into two halves of faces, at the median of the face
// centroids along the longest side of its bounding box (ties by face index); each half is
// coarsened with the cut held, on a second thread when the compute threads allow, and the halves
// are joined again along the cut, whose vertices are the whole mesh's. The cut depends on the
// input only, so the result is the same on one thread as on two. The cut stays at the input's
// resolution; the remeshing that follows evens it out. Should a half or the joined surface not
// be a manifold, the whole mesh is coarsened in one pass instead.
template <class EdgeMap, class IdMap, class FaceMap, class PatchMap>
void coarsen(Mesh& mesh, EdgeMap& econ, IdMap& old_id, FaceMap& in_region, PatchMap& patch,
             double below, std::size_t in_halves_from) {
  if (mesh.number_of_faces() < in_halves_from) {
    collapse_shortest(mesh, econ, old_id, below, false);
    return;
  }
  std::vector<FI> order(mesh.faces().begin(), mesh.faces().end());
  CGAL::Bbox_3 box;
  for (VI v : mesh.vertices()) box += mesh.point(v).bbox();
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (box.max(a) - box.min(a) > box.max(axis) - box.min(axis)) axis = a;
  const auto centroid = [&](FI f) {
    double c = 0.0;
    for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) c += mesh.point(v)[axis];
    return c;
  };
  std::vector<std::pair<double, FI>> keyed;
  keyed.reserve(order.size());
  for (FI f : order) keyed.emplace_back(centroid(f), f);
  const auto middle = keyed.begin() + static_cast<std::ptrdiff_t>(keyed.size() / 2);
  std::nth_element(keyed.begin(), middle, keyed.end());
  std::vector<char> second(mesh.num_faces(), 0);
  for (auto it = middle; it != keyed.end(); ++it) second[it->second.idx()] = 1;
  // Each half must be a manifold: around every vertex, the faces of a half must form one fan.
  // Where a half's faces around a vertex come in several runs, all the faces around it go to
  // the first half, round by round; should pinches remain, one pass over the whole mesh.
  std::vector<int> ring;
  const auto pinched = [&](VI v) {
    if (mesh.halfedge(v) == Mesh::null_halfedge()) return false;  // no face: nothing to pinch
    ring.clear();
    for (FI f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
      ring.push_back(f == Mesh::null_face() ? -1 : second[f.idx()]);
    std::array<int, 2> runs{0, 0};
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const int here = ring[i], before = ring[(i + ring.size() - 1) % ring.size()];
      if (here >= 0 && here != before) ++runs[static_cast<std::size_t>(here)];
    }
    return runs[0] > 1 || runs[1] > 1;
  };
  bool manifold_halves = false;
  for (int round = 0; round < 50 && !manifold_halves; ++round) {
    std::vector<VI> pinches;
    for (VI v : mesh.vertices())
      if (pinched(v)) pinches.push_back(v);
    manifold_halves = pinches.empty();
    for (VI v : pinches)
      for (FI f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
        if (f != Mesh::null_face()) second[f.idx()] = 0;
  }
  if (!manifold_halves) {
    collapse_shortest(mesh, econ, old_id, below, false);
    return;
  }

  std::array<Half, 2> halves;
  for (int k = 0; k < 2; ++k) {
    Half& half = halves[static_cast<std::size_t>(k)];
    half.whole = half.mesh.add_property_map<VI, int>("v:whole", -1).first;
    half.held = half.mesh.add_property_map<EI, bool>("e:held", false).first;
    half.given = half.mesh.add_property_map<EI, bool>("e:given", false).first;
    half.patch = half.mesh.add_property_map<FI, int>("f:patch", 0).first;
    std::vector<VI> local(mesh.num_vertices(), Mesh::null_vertex());
    for (FI f : order) {
      if (second[f.idx()] != k) continue;
      std::array<VI, 3> corners;
      int c = 0;
      for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
        if (local[v.idx()] == Mesh::null_vertex()) {
          local[v.idx()] = half.mesh.add_vertex(mesh.point(v));
          half.whole[local[v.idx()]] = static_cast<int>(v.idx());
        }
        corners[static_cast<std::size_t>(c++)] = local[v.idx()];
      }
      const FI added = half.mesh.add_face(corners[0], corners[1], corners[2]);
      if (added == Mesh::null_face()) {  // not a manifold half after all: one pass instead
        collapse_shortest(mesh, econ, old_id, below, false);
        return;
      }
      half.patch[added] = patch[f];
    }
    for (EI e : half.mesh.edges()) {
      const VI a(static_cast<Mesh::size_type>(half.whole[half.mesh.vertex(e, 0)]));
      const VI b(static_cast<Mesh::size_type>(half.whole[half.mesh.vertex(e, 1)]));
      half.given[e] = econ[mesh.edge(mesh.halfedge(a, b))];
      half.held[e] = half.given[e] || half.mesh.is_border(e);
    }
  }
  const auto run = [&](int k) {
    Half& half = halves[static_cast<std::size_t>(k)];
    collapse_shortest(half.mesh, half.held, half.whole, below, true);
  };
  run_pair([&] { run(0); }, [&] { run(1); });

  // Join, first into plain arrays: the vertices on held edges (the cut and the whole mesh's
  // constraints) are whole-mesh vertices and are shared; every other vertex is its half's own.
  std::vector<Point> points;
  std::vector<int> old;
  std::vector<std::array<std::size_t, 3>> faces;
  std::vector<int> face_patch;
  std::vector<std::pair<std::size_t, std::size_t>> given;
  std::vector<std::size_t> joined(mesh.num_vertices(), SIZE_MAX);
  for (Half& half : halves) {
    auto pinned = half.mesh.add_property_map<VI, bool>("v:pinned", false).first;
    for (EI e : half.mesh.edges())
      if (half.held[e]) pinned[half.mesh.vertex(e, 0)] = pinned[half.mesh.vertex(e, 1)] = true;
    std::vector<std::size_t> to(half.mesh.num_vertices(), SIZE_MAX);
    for (VI v : half.mesh.vertices()) {
      const auto w = static_cast<std::size_t>(half.whole[v]);
      if (pinned[v] && joined[w] != SIZE_MAX) {
        to[v.idx()] = joined[w];
        continue;
      }
      to[v.idx()] = points.size();
      points.push_back(half.mesh.point(v));
      old.push_back(old_id[VI(static_cast<Mesh::size_type>(w))]);
      if (pinned[v]) joined[w] = to[v.idx()];
    }
    for (FI f : half.mesh.faces()) {
      std::array<std::size_t, 3> corners{};
      int c = 0;
      for (VI v : CGAL::vertices_around_face(half.mesh.halfedge(f), half.mesh))
        corners[static_cast<std::size_t>(c++)] = to[v.idx()];
      faces.push_back(corners);
      face_patch.push_back(half.patch[f]);
    }
    for (EI e : half.mesh.edges())
      if (half.given[e]) given.emplace_back(to[half.mesh.vertex(e, 0).idx()], to[half.mesh.vertex(e, 1).idx()]);
  }
  // The joined surface must be a manifold; should it not be, the whole mesh (still untouched)
  // is coarsened in one pass instead.
  {
    Mesh check;
    for (const Point& p : points) check.add_vertex(p);
    for (const auto& f : faces)
      if (check.add_face(VI(static_cast<Mesh::size_type>(f[0])), VI(static_cast<Mesh::size_type>(f[1])),
                         VI(static_cast<Mesh::size_type>(f[2]))) == Mesh::null_face()) {
        collapse_shortest(mesh, econ, old_id, below, false);
        return;
      }
  }
  // The same additions in the same order into the (cleared) mesh, with its property maps.
  mesh.clear_without_removing_property_maps();
  for (std::size_t v = 0; v < points.size(); ++v) old_id[mesh.add_vertex(points[v])] = old[v];
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto& f = faces[k];
    const FI n = mesh.add_face(VI(static_cast<Mesh::size_type>(f[0])), VI(static_cast<Mesh::size_type>(f[1])),
                               VI(static_cast<Mesh::size_type>(f[2])));
    patch[n] = face_patch[k];
    in_region[n] = true;
  }
  for (const auto& [a, b] : given)
    econ[mesh.edge(mesh.halfedge(VI(static_cast<Mesh::size_type>(a)), VI(static_cast<Mesh::size_type>(b))))] = true;
}

}  // namespace

CgalRemeshOutput cgal_remesh(const CgalRemeshInput& in) {
  const std::vector<Vec3>& X = *in.positions;
  const std::vector<FaceIndices>& F = *in.faces;
  Mesh mesh;
  for (const Vec3& p : X) mesh.add_vertex(to_point(p));
  for (const FaceIndices& f : F) mesh.add_face(VI(f[0]), VI(f[1]), VI(f[2]));

  auto old_id = mesh.add_property_map<VI, int>("v:old", -1).first;
  auto vfixed = mesh.add_property_map<VI, bool>("v:fixed", false).first;
  auto econ = mesh.add_property_map<EI, bool>("e:constrained", false).first;
  auto in_region = mesh.add_property_map<FI, bool>("f:region", false).first;
  auto patch = mesh.add_property_map<FI, int>("f:patch", 0).first;  // 2 * sheet + in band
  for (VI v : mesh.vertices()) {
    old_id[v] = static_cast<int>(v.idx());
    vfixed[v] = v.idx() < in.constrained_vertices.size() && in.constrained_vertices[v.idx()];
  }
  for (FI f : mesh.faces()) in_region[f] = in.region[f.idx()];

  // The input polylines (constraints and open boundaries) for the projection of the vertices
  // that lie on them; the input surface for all others.
  std::vector<Segment> segments;
  for (const auto& [a, b] : in.constrained_edges) {
    const auto h = mesh.halfedge(VI(a), VI(b));
    econ[mesh.edge(h)] = true;
  }
  for (EI e : mesh.edges()) {
    if (mesh.is_border(e)) econ[e] = true;
    if (econ[e])
      segments.emplace_back(mesh.point(mesh.vertex(e, 0)), mesh.point(mesh.vertex(e, 1)));
  }
  // Sheets: the faces connected across unconstrained edges (a patch and its host, the two
  // sides of a seam, are different sheets). A vertex is projected, and located, only on its own
  // sheet of the input: on the nearest surface, a patch laid over a slit would fall onto the
  // host beneath it. The patch id CGAL carries to new faces is 2 * sheet + (in the band).
  std::vector<int> sheet(F.size(), -1);
  int sheets = 0;
  for (FI seed : mesh.faces()) {
    if (sheet[seed.idx()] >= 0) continue;
    std::vector<FI> stack{seed};
    sheet[seed.idx()] = sheets;
    while (!stack.empty()) {
      const FI f = stack.back();
      stack.pop_back();
      for (auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) {
        if (econ[mesh.edge(h)]) continue;
        const FI g = mesh.face(mesh.opposite(h));
        if (g != Mesh::null_face() && sheet[g.idx()] < 0) {
          sheet[g.idx()] = sheets;
          stack.push_back(g);
        }
      }
    }
    ++sheets;
  }
  for (FI f : mesh.faces()) patch[f] = 2 * sheet[f.idx()];
  const Mesh original = mesh;
  std::vector<std::vector<FI>> sheet_faces(static_cast<std::size_t>(sheets));
  for (FI f : original.faces()) sheet_faces[static_cast<std::size_t>(sheet[f.idx()])].push_back(f);
  std::vector<std::unique_ptr<FaceTree>> surface;
  for (const auto& fs : sheet_faces) {
    surface.push_back(std::make_unique<FaceTree>(fs.begin(), fs.end(), original));
    surface.back()->accelerate_distance_queries();
  }
  SegmentTree polylines(segments.cbegin(), segments.cend());
  if (!segments.empty()) polylines.accelerate_distance_queries();
  // The sheet of a vertex of the mesh being remeshed: that of its first face.
  const auto sheet_of = [&](VI v) {
    for (FI f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
      if (f != Mesh::null_face()) return patch[f] / 2;
    return 0;
  };

  const auto on_polyline = [&](VI v) {
    for (auto h : CGAL::halfedges_around_target(mesh.halfedge(v), mesh))
      if (econ[mesh.edge(h)]) return true;
    return false;
  };
  const auto project = [&](VI v) {
    const Point& p = mesh.point(v);
    if (!segments.empty() && on_polyline(v)) return polylines.closest_point(p);
    return surface[static_cast<std::size_t>(sheet_of(v))]->closest_point(p);
  };

  dissolve_boundary_vertices(mesh, econ, vfixed, old_id, in_region, in.removed_boundary_vertices);

  if (in.coarsen_below > 0.0) {
    coarsen(mesh, econ, old_id, in_region, patch, in.coarsen_below, in.coarsen_in_halves_from);
    for (VI v : mesh.vertices())
      if (!mesh.is_border(v) && !on_polyline(v)) mesh.point(v) = project(v);
  }

  for (const RemeshBand& band : in.bands) {
    std::vector<FI> range;
    for (FI f : mesh.faces()) {
      patch[f] &= ~1;
      if (!in_region[f]) continue;
      if (band.reach >= 0.0) {
        Vec3 c = Vec3::Zero();
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) c += to_vec(mesh.point(v));
        if (distance_to_polyline(c / 3.0, in.band_curve) > band.reach) continue;
      }
      patch[f] |= 1;
      range.push_back(f);
    }
    if (range.empty()) continue;
    for (int it = 0; it < in.iterations; ++it) {
      // Split, collapse, flip and project; the tangential relaxation is run below instead of
      // CGAL's own, which in CGAL 5.5 ignores vertex_is_constrained_map and moves fixed
      // vertices.
      PMP::isotropic_remeshing(range, band.target_edge_length, mesh,
                               CGAL::parameters::number_of_iterations(1)
                                   .number_of_relaxation_steps(0)
                                   .edge_is_constrained_map(econ)
                                   .vertex_is_constrained_map(vfixed)
                                   .face_patch_map(patch)
                                   .protect_constraints(false)
                                   .collapse_constraints(true)
                                   .relax_constraints(false)
                                   .projection_functor(project));
      range.clear();
      for (FI f : mesh.faces())
        if (patch[f] & 1) range.push_back(f);
      // Vertices that may move: inside the band and not fixed; those on a constrained polyline
      // slide along it (and are projected back onto the input polyline).
      std::vector<VI> inner;
      for (FI f : range)
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) inner.push_back(v);
      std::sort(inner.begin(), inner.end());
      inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
      auto held = mesh.add_property_map<VI, bool>("v:held", false).first;
      for (VI v : inner) {
        bool h = vfixed[v];
        for (FI f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
          h = h || f == Mesh::null_face() || !(patch[f] & 1);
        held[v] = h;
      }
      PMP::tangential_relaxation(inner, mesh,
                                 CGAL::parameters::number_of_iterations(1)
                                     .edge_is_constrained_map(econ)
                                     .vertex_is_constrained_map(held)
                                     .relax_constraints(true));
      for (VI v : inner)
        if (!held[v]) mesh.point(v) = project(v);
      mesh.remove_property_map(held);
    }
    for (FI f : mesh.faces())
      if (patch[f] & 1) in_region[f] = true;
  }

  // A face outside the region that the bands changed (an edge of the region's rim was split or
  // collapsed: it has a new or moved corner, or corners no input face has) is a face the remesh
  // made.
  // Old faces by their vertex triple, to recognise faces the remesh left alone (here and in the
  // output).
  std::map<std::array<int, 3>, int> old_face;
  for (std::size_t f = 0; f < F.size(); ++f) {
    std::array<int, 3> key{F[f][0], F[f][1], F[f][2]};
    std::sort(key.begin(), key.end());
    old_face.emplace(key, static_cast<int>(f));
  }
  if (in.rim_faces_in_region) {
    for (FI f : mesh.faces()) {
      if (in_region[f]) continue;
      std::array<int, 3> key{};
      int k = 0;
      bool changed = false;
      for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
        key[k++] = old_id[v];
        changed = changed || old_id[v] < 0 || mesh.point(v) != to_point(X[static_cast<std::size_t>(old_id[v])]);
      }
      std::sort(key.begin(), key.end());
      if (changed || old_face.count(key) == 0) in_region[f] = true;
    }
  }
  delaunay_flips(mesh, econ, in_region);
  for (int round = 0; round < 4; ++round) {
    if (collapse_needles(mesh, econ, vfixed, old_id, in_region, on_polyline) == 0) break;
    delaunay_flips(mesh, econ, in_region);
  }
  if (in.raise_angles_below_deg > 0.0)
    for (int round = 0; round < 4; ++round) {
      if (raise_smallest_angles(mesh, vfixed, in_region, on_polyline, project,
                                in.raise_angles_below_deg * M_PI / 180.0) == 0)
        break;
      delaunay_flips(mesh, econ, in_region);
    }

  if (in.max_deviation > 0.0) {
    // Where the surface bends faster than the target length can follow: split the longest
    // edge of every face that strays too far, at its midpoint moved onto the input.
    const auto nearest_on = [&](const Point& q, FI f, bool on_line) {
      if (on_line) return polylines.closest_point(q);
      return surface[static_cast<std::size_t>(patch[f] / 2)]->closest_point(q);
    };
    const double shortest_split = 2.0 * in.bands.back().target_edge_length / 3.0;
    const double shortest_border_split = in.bands.back().target_edge_length;
    for (int round = 0; round < 6; ++round) {
      std::vector<EI> split;
      for (FI f : mesh.faces()) {
        std::array<Vec3, 3> p;
        std::array<HI, 3> hs;
        int k = 0;
        for (HI h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh)) {
          hs[k] = h;
          p[k++] = to_vec(mesh.point(mesh.target(h)));
        }
        double worst = 0.0;
        for (const Vec3& q : {Vec3((p[0] + p[1] + p[2]) / 3.0), Vec3(0.5 * (p[0] + p[1])),
                              Vec3(0.5 * (p[1] + p[2])), Vec3(0.5 * (p[2] + p[0]))})
          worst = std::max(worst, (to_vec(nearest_on(to_point(q), f, false)) - q).norm());
        if (worst <= in.max_deviation) continue;
        // hs[k] runs from corner k-1 to corner k: its length is |p[k] - p[k-1]|. No edge is
        // split below a third of the target (a quarter where the face strays more than twice
        // the allowed distance: a shoulder sharper than the target can follow), and none on the
        // open boundary below half of it (a short edge there makes a thin face that neither a
        // flip nor smoothing can mend).
        int longest = -1;
        double longest_length = 0.0;
        for (int j = 0; j < 3; ++j) {
          const double l = (p[j] - p[(j + 2) % 3]).norm();
          if (l > longest_length) longest_length = l, longest = j;
        }
        if (longest < 0) continue;
        const double shortest = mesh.is_border(mesh.edge(hs[longest]))
                                    ? shortest_border_split
                                    : (worst > 2.0 * in.max_deviation ? 0.75 : 1.0) * shortest_split;
        if (longest_length <= shortest) continue;
        split.push_back(mesh.edge(hs[longest]));
      }
      std::sort(split.begin(), split.end());
      split.erase(std::unique(split.begin(), split.end()), split.end());
      if (split.empty()) break;
      for (EI e : split) {
        const HI h = mesh.halfedge(e);
        const bool line = econ[e];
        const FI f = mesh.is_border(h) ? mesh.face(mesh.opposite(h)) : mesh.face(h);
        const Point mid = nearest_on(CGAL::midpoint(mesh.point(mesh.source(h)), mesh.point(mesh.target(h))), f, line);
        const int patch_h = mesh.is_border(h) ? 0 : patch[mesh.face(h)];
        const int patch_o = mesh.is_border(mesh.opposite(h)) ? 0 : patch[mesh.face(mesh.opposite(h))];
        // hnew: source(h) -> v, followed by h: v -> target(h) (CGAL::Euler::split_edge).
        const HI hnew = CGAL::Euler::split_edge(h, mesh);
        mesh.point(mesh.target(hnew)) = mid;
        econ[mesh.edge(hnew)] = line;
        for (const auto& [side, side_patch] : {std::pair{hnew, patch_h}, std::pair{mesh.opposite(h), patch_o}}) {
          if (mesh.is_border(side)) continue;
          const HI other = side == hnew ? mesh.next(h) : mesh.next(mesh.opposite(hnew));
          const HI diagonal = CGAL::Euler::split_face(side, other, mesh);
          for (const FI g : {mesh.face(diagonal), mesh.face(mesh.opposite(diagonal))}) {
            patch[g] = side_patch;
            in_region[g] = true;
          }
        }
      }
      delaunay_flips(mesh, econ, in_region);
    }
  }
  if (in.repair_below_deg > 0.0) {
    const double below = in.repair_below_deg * M_PI / 180.0;
    // A thin face on a short open-boundary edge: both ends of the edge move along the
    // boundary, each to midway between its two boundary neighbours (on the input polyline), as
    // no interior move can widen that face. A move that would fold a face is not made.
    for (HI h : mesh.halfedges()) {
      if (!mesh.is_border(h)) continue;
      const HI inner = mesh.opposite(h);
      const Point &a = mesh.point(mesh.source(inner)), &b = mesh.point(mesh.target(inner));
      const Point& c = mesh.point(mesh.target(mesh.next(inner)));
      if (std::sqrt(CGAL::squared_distance(a, b)) >= 0.5 * in.bands.back().target_edge_length ||
          smallest_angle(a, b, c) >= below)
        continue;
      for (const VI r : {mesh.source(h), mesh.target(h)}) {
        if (vfixed[r]) continue;
        // The border half-edges into and out of r.
        HI into = Mesh::null_halfedge();
        for (HI g : CGAL::halfedges_around_target(mesh.halfedge(r), mesh))
          if (mesh.is_border(g)) into = g;
        if (into == Mesh::null_halfedge()) continue;
        const VI before = mesh.source(into), after = mesh.target(mesh.next(into));
        const Point old_place = mesh.point(r);
        const Point place = polylines.closest_point(CGAL::midpoint(mesh.point(before), mesh.point(after)));
        std::vector<std::pair<FI, Vec3>> normals;
        for (FI f : CGAL::faces_around_target(mesh.halfedge(r), mesh))
          if (f != Mesh::null_face()) {
            const auto p = corners_after(mesh, f, Mesh::null_vertex(), Point());
            normals.emplace_back(f, normal_of(p[0], p[1], p[2]));
          }
        mesh.point(r) = place;
        for (const auto& [f, n_old] : normals) {
          const auto p = corners_after(mesh, f, Mesh::null_vertex(), Point());
          const Vec3 n_new = normal_of(p[0], p[1], p[2]);
          if (!(n_new.dot(n_old) > 0.2 * n_new.norm() * n_old.norm())) mesh.point(r) = old_place;
        }
      }
    }
    auto held = mesh.add_property_map<VI, bool>("v:repair_held", false).first;
    for (VI v : mesh.vertices()) held[v] = vfixed[v] || mesh.is_border(v) || on_polyline(v);
    for (int round = 0; round < 6; ++round) {
      std::vector<FI> region;
      for (FI f : mesh.faces()) {
        std::array<Point, 3> p;
        int k = 0;
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) p[k++] = mesh.point(v);
        if (!in_region[f] || smallest_angle(p[0], p[1], p[2]) >= below) continue;
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
          for (FI g : CGAL::faces_around_target(mesh.halfedge(v), mesh))
            if (g != Mesh::null_face() && in_region[g]) region.push_back(g);
      }
      std::sort(region.begin(), region.end());
      region.erase(std::unique(region.begin(), region.end()), region.end());
      if (region.empty()) break;
      PMP::angle_and_area_smoothing(region, mesh,
                                    CGAL::parameters::number_of_iterations(1)
                                        .use_angle_smoothing(true)
                                        .use_area_smoothing(false)
                                        .do_project(false)
                                        .vertex_is_constrained_map(held));
      for (FI f : region)
        for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
          if (!held[v]) mesh.point(v) = project(v);
      delaunay_flips(mesh, econ, in_region);
      if (collapse_needles(mesh, econ, vfixed, old_id, in_region, on_polyline, below) > 0) {
        delaunay_flips(mesh, econ, in_region);
        for (VI v : mesh.vertices()) held[v] = vfixed[v] || mesh.is_border(v) || on_polyline(v);
      }
    }
    mesh.remove_property_map(held);
  }

  const auto locate = [&](const Vec3& p, int on_sheet) {
    const auto [q, face] = surface[static_cast<std::size_t>(on_sheet)]->closest_point_and_primitive(to_point(p));
    SurfaceLocation loc;
    loc.face = static_cast<int>(face.idx());
    const FaceIndices& t = F[face.idx()];
    loc.bary = closest_point_barycentric(p, X[t[0]], X[t[1]], X[t[2]]);
    return loc;
  };

  CgalRemeshOutput out;
  std::vector<int> index(mesh.number_of_vertices() + mesh.number_of_removed_vertices(), -1);
  for (VI v : mesh.vertices()) {
    index[v.idx()] = static_cast<int>(out.positions.size());
    const Vec3 p = to_vec(mesh.point(v));
    const int o = old_id[v];
    const bool moved = o < 0 || p != X[static_cast<std::size_t>(o)];
    out.positions.push_back(p);
    out.old_vertex.push_back(o);
    out.moved.push_back(moved);
    out.vertex_location.push_back(moved ? locate(p, sheet_of(v)) : SurfaceLocation{});
  }
  for (FI f : mesh.faces()) {
    FaceIndices t{};
    int k = 0;
    for (VI v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[k++] = index[v.idx()];
    int same = -1;
    const int a = out.old_vertex[t[0]], b = out.old_vertex[t[1]], c = out.old_vertex[t[2]];
    if (!out.moved[t[0]] && !out.moved[t[1]] && !out.moved[t[2]]) {
      std::array<int, 3> key{a, b, c};
      std::sort(key.begin(), key.end());
      if (const auto it = old_face.find(key); it != old_face.end()) {
        // Same corners; keep the old face's corner order (same orientation in a manifold).
        const FaceIndices& of = F[static_cast<std::size_t>(it->second)];
        for (int r = 0; r < 3; ++r)
          if (out.old_vertex[t[r]] == of[0]) {
            const FaceIndices turned{t[r], t[(r + 1) % 3], t[(r + 2) % 3]};
            if (out.old_vertex[turned[1]] == of[1]) {
              t = turned;
              same = it->second;
            }
          }
      }
    }
    out.faces.push_back(t);
    out.region.push_back(in_region[f]);
    out.old_face.push_back(same);
    out.face_location.push_back(
        same >= 0 ? SurfaceLocation{}
                  : locate((out.positions[t[0]] + out.positions[t[1]] + out.positions[t[2]]) / 3.0,
                           patch[f] / 2));
  }
  for (EI e : mesh.edges())
    if (econ[e] && !mesh.is_border(e))
      out.constrained_edges.emplace_back(index[mesh.vertex(e, 0).idx()],
                                         index[mesh.vertex(e, 1).idx()]);
  return out;
}

}  // namespace sutura::engine::detail
