#include "sutura/engine/surgery/incise.hpp"

#include <algorithm>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "mesh_walk.hpp"
#include "surface_path.hpp"
#include "sutura/engine/errors.hpp"
#include "triangle_soup.hpp"

namespace sutura::engine {

IncisionMode parse_incision_mode(const std::string& name) {
  if (name == "snap") return IncisionMode::SnapToEdges;
  if (name == "cut") return IncisionMode::CutThroughFaces;
  throw InvalidArgument("unknown incision mode \"" + name + "\" (expected \"snap\" or \"cut\")");
}

namespace {

using detail::PathEvent;

/// Crossings of the traced curve within this fraction of an edge of its end, and curve points
/// within it (barycentric) of an edge or corner, are that vertex or edge: the curve's events
/// on the mesh are exact up to it.
constexpr double kExactCrossing = 1e-6;

/// Relative tolerance (of an edge, or a barycentric coordinate) under which a curve point or
/// crossing is taken to be on the existing vertex or edge: it only absorbs rounding, so the
/// cut stays on the drawn curve and no zero-length edge is made.
constexpr double kSnap = 1e-9;

// Builds the cut in the soup from the traced curve (events on the original mesh, each two
// consecutive ones in a common original face). Each piece between two events is a straight
// segment in one original face; it is walked through the soup faces that now tile that face
// (earlier pieces may have split it), splitting every soup edge it crosses. Each vertex of the
// cut therefore shares a soup face with the one before it, so consecutive cut vertices are
// joined by an edge by construction, however the curve points are spaced.
//
// A point or crossing within kSnap (relative) or `snap_distance` (mm) of an existing vertex
// or edge is put there instead; with snap_distance = 0 the cut lies on the curve up to rounding.
class CutBuilder {
 public:
  CutBuilder(const SurfaceMesh& mesh, detail::TriangleSoup& soup, double snap_distance)
      : mesh_(mesh), soup_(soup), snap_(snap_distance) {}

  [[nodiscard]] const std::vector<int>& path() const { return path_; }

  // The soup vertex at event e (the first of the curve).
  void start(const PathEvent& e) {
    const FaceId f0 = detail::event_faces(mesh_, e).front();
    Eigen::Vector3d local;
    const int f = soup_.locate(f0, detail::event_bary(mesh_, e, f0), local);
    if (f < 0) throw Error("incise: internal error: curve point not found in its face");
    append(insert_in_face(f, local));
  }

  // Extends the cut from its last vertex (at event `from`) straight to event `to`.
  void extend(const PathEvent& from, const PathEvent& to) {
    const FaceId parent = common_face(from, to);
    const Eigen::Vector3d b = detail::event_bary(mesh_, to, parent);
    // A straight segment passes through each soup face of `parent` at most once.
    const std::size_t max_steps = soup_.faces_of(parent).size() + 16;
    for (std::size_t step = 0;; ++step) {
      if (step > max_steps)
        throw Error("incise: internal error: the cut could not be followed through a face");
      const int u = path_.back();
      // The soup face of `parent` at u that the segment u -> b enters: the target's local
      // coordinates at the two other corners are >= 0 there (up to rounding: best one).
      int best = -1, kb = 0;
      double best_score = -std::numeric_limits<double>::infinity();
      Eigen::Vector3d lb;
      for (const int f : soup_.faces_of(parent)) {
        const FaceIndices& fv = soup_.face(f);
        int k = 0;
        while (k < 3 && fv[k] != u) ++k;
        if (k == 3) continue;
        const Eigen::Vector3d l = local_coordinates(f, b);
        const double score = std::min(l[(k + 1) % 3], l[(k + 2) % 3]);
        if (score > best_score) best_score = score, best = f, kb = k, lb = l;
      }
      if (best < 0) throw Error("incise: internal error: the cut left the face it runs through");
      if (lb[kb] >= -kSnap) {  // the target is in this soup face
        append(insert_in_face(best, lb));
        return;
      }
      // Leave through the edge opposite u, at the crossing of the segment with it.
      const FaceIndices fv = soup_.face(best);
      const int a = fv[(kb + 1) % 3], c = fv[(kb + 2) % 3];
      const double la = std::max(lb[(kb + 1) % 3], 0.0), lc = std::max(lb[(kb + 2) % 3], 0.0);
      const double t = la + lc > 0.0 ? lc / (la + lc) : 0.5;
      append(split_edge(a, c, t));
    }
  }

 private:
  Eigen::Vector3d local_coordinates(int f, const Eigen::Vector3d& b) const {
    // Rows of B are the corners' coordinates in the parent: b^T = l^T B.
    return soup_.maps().faces[f].bary.transpose().fullPivLu().solve(b);
  }

  // The soup vertex at local coordinates l of soup face f: a corner, a split of an edge, or a
  // split of the face.
  int insert_in_face(int f, Eigen::Vector3d l) {
    for (int k = 0; k < 3; ++k) l[k] = std::max(l[k], 0.0);
    l /= l.sum();
    const FaceIndices fv = soup_.face(f);
    const Vec3 p[3] = {soup_.position(fv[0]), soup_.position(fv[1]), soup_.position(fv[2])};
    const Vec3 x = l[0] * p[0] + l[1] * p[1] + l[2] * p[2];
    int kmax = 0, knear = 0;
    for (int k = 1; k < 3; ++k) {
      if (l[k] > l[kmax]) kmax = k;
      if ((x - p[k]).norm() < (x - p[knear]).norm()) knear = k;
    }
    if (l[kmax] >= 1.0 - kSnap) return fv[kmax];
    // On an edge up to rounding (always so for a point on an edge of the original face): stay
    // on that edge, so that the vertex is also in the next original face of the curve.
    for (int k = 0; k < 3; ++k)
      if (l[k] <= kSnap) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        return split_edge(fv[i], fv[j], l[j] / (l[i] + l[j]));
      }
    if ((x - p[knear]).norm() <= snap_) return fv[knear];
    // The distance to the edge opposite corner k is l[k] times that corner's height.
    const double twice_area = (p[1] - p[0]).cross(p[2] - p[0]).norm();
    int kedge = -1;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double d = l[k] * twice_area / (p[(k + 2) % 3] - p[(k + 1) % 3]).norm();
      if (d <= snap_ && d < best) best = d, kedge = k;
    }
    if (kedge >= 0) {  // the foot of the perpendicular (a thin face's corner can be far)
      const int j = (kedge + 1) % 3, k = (kedge + 2) % 3;
      const Vec3 e = p[k] - p[j];
      return split_edge(fv[j], fv[k], std::clamp((x - p[j]).dot(e) / e.squaredNorm(), 0.0, 1.0));
    }
    return soup_.split_face(f, l);
  }

  // The soup vertex at (1 - t) a + t c on edge {a, c}: an end, or a new vertex splitting it.
  int split_edge(int a, int c, double t) {
    const double len = (soup_.position(c) - soup_.position(a)).norm();
    const double da = t * len, dc = (1.0 - t) * len;
    if (t <= kSnap || (da <= snap_ && da <= dc)) return a;
    if (t >= 1.0 - kSnap || dc <= snap_) return c;
    // Splitting an edge of the cut itself would separate two consecutive cut vertices: the
    // curve crosses (or touches) itself there.
    if (cut_edges_.count({std::min(a, c), std::max(a, c)}))
      throw InvalidArgument("the incision crosses itself at " +
                            detail::point_text((1.0 - t) * soup_.position(a) +
                                               t * soup_.position(c)));
    return soup_.split_edge(a, c, t);
  }

  void append(int v) {
    if (!path_.empty() && path_.back() == v) return;
    if (!on_path_.insert(v).second)
      throw InvalidArgument("the incision crosses itself at " +
                            detail::point_text(soup_.position(v)));
    if (!path_.empty()) cut_edges_.insert({std::min(v, path_.back()), std::max(v, path_.back())});
    path_.push_back(v);
  }

  FaceId common_face(const PathEvent& a, const PathEvent& b) const {
    const std::vector<FaceId> fb = detail::event_faces(mesh_, b);
    for (const FaceId f : detail::event_faces(mesh_, a))
      if (std::find(fb.begin(), fb.end(), f) != fb.end()) return f;
    throw Error("incise: internal error: consecutive curve events share no face");
  }

  const SurfaceMesh& mesh_;
  detail::TriangleSoup& soup_;
  const double snap_;
  std::vector<int> path_;
  std::set<int> on_path_;
  std::set<std::pair<int, int>> cut_edges_;
};

// Faces on the left of the cut at path vertex i (those that get the new copy).
std::vector<FaceId> left_wedge(const SurfaceMesh& mesh, const std::vector<VertexId>& c,
                               std::size_t i) {
  std::vector<FaceId> wedge;
  const std::size_t m = c.size() - 1;
  if (i < m) {
    HalfedgeId h = detail::find_halfedge(mesh, c[i], c[i + 1]);
    const HalfedgeId stop = i > 0 ? detail::find_halfedge(mesh, c[i], c[i - 1]) : HalfedgeId();
    while (true) {
      wedge.push_back(SurfaceMesh::face(h));
      const HalfedgeId nh = mesh.twin(SurfaceMesh::prev(h));
      if (!nh.valid() || nh == stop) break;
      h = nh;
    }
  } else {
    // Last vertex on the boundary: from the fan start up to the face right of the last edge.
    HalfedgeId h = mesh.vertex_halfedge(c[i]);
    const HalfedgeId stop = detail::find_halfedge(mesh, c[i], c[i - 1]);
    while (h != stop) {
      wedge.push_back(SurfaceMesh::face(h));
      h = mesh.twin(SurfaceMesh::prev(h));
    }
  }
  return wedge;
}

// A face the refinement made (untouched original faces are the input's) that would count as
// degenerate in SurfaceMesh::validate() (area below 1e-10 of the squared mean edge length),
// with a margin of 2 for the mean's change when the cut opens; or -1.
int degenerate_face(const detail::TriangleSoup& soup, std::size_t original_faces) {
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t f = 0; f < soup.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = soup.face(f)[k], v = soup.face(f)[(k + 1) % 3];
      if (u < v || soup.face_with_edge(v, u) < 0) {
        sum += (soup.position(v) - soup.position(u)).norm();
        ++count;
      }
    }
  const double mean = sum / static_cast<double>(std::max<std::size_t>(count, 1));
  const double min_area = 2e-10 * mean * mean;
  for (std::size_t parent = 0; parent < original_faces; ++parent) {
    const std::vector<int>& fs = soup.faces_of(FaceId(parent));
    if (fs.size() < 2) continue;
    for (const int f : fs) {
      const FaceIndices& v = soup.face(f);
      const double twice_area = (soup.position(v[1]) - soup.position(v[0]))
                                    .cross(soup.position(v[2]) - soup.position(v[0]))
                                    .norm();
      if (0.5 * twice_area < min_area) return f;
    }
  }
  return -1;
}

// `refined` (an edit of the mesh passed to incise by `maps`, the cut `c` among its constrained
// edges) remeshed with `rp`: the new mesh, maps from the mesh passed to incise, the cut on it,
// and the band's quality before and after.
struct CutRemesh {
  SurfaceMesh mesh;
  EditMaps maps;
  std::vector<VertexId> cut;
  MeshQuality before, after;
};

CutRemesh remesh_keeping_cut(const RemeshParams& rp, const SurfaceMesh& refined, const EditMaps& maps,
                             const std::vector<VertexId>& c) {
  RemeshResult r = remesh(refined, rp);
  // The cut again, as the chain of constrained edges from the (kept) first vertex to the last.
  std::vector<VertexId> image(refined.num_vertices());
  for (std::size_t v = 0; v < r.maps.vertices.size(); ++v) {
    const VertexOrigin& o = r.maps.vertices[v];
    if (o.kind == VertexOriginKind::Copy) image[o.parents[0].index()] = VertexId(v);
  }
  const VertexId first = image[c.front().index()], last = image[c.back().index()];
  if (!first.valid() || !last.valid())
    throw Error("incise: internal error: the remesh moved an end of the cut");
  std::vector<std::vector<VertexId>> along(r.mesh.num_vertices());
  for (const auto& [a, b] : r.constrained_edges) {
    along[a.index()].push_back(b);
    along[b.index()].push_back(a);
  }
  std::vector<VertexId> chain{first};
  while (chain.back() != last) {
    const VertexId at = chain.back();
    VertexId next;
    for (const VertexId w : along[at.index()])
      if (chain.size() < 2 || w != chain[chain.size() - 2]) next = w;
    if (!next.valid() || along[at.index()].size() > 2 || chain.size() > r.mesh.num_vertices())
      throw Error("incise: internal error: the remeshed cut is not one polyline");
    chain.push_back(next);
  }
  CutRemesh out;
  out.maps = compose(maps, r.maps);
  out.mesh = std::move(r.mesh);
  out.cut = std::move(chain);
  out.before = r.before;
  out.after = r.after;
  return out;
}

// Remeshes the band around the traced cut `c` of `refined` (an edit of `mesh` by `maps`), the
// cut kept as a constrained polyline; updates all three to the remeshed mesh. Where the band
// keeps an angle below params.repair_below_deg, the band is remeshed again from the raw cut,
// finer at the cut (kRepairTargets), and the best of the attempts is kept.
void remesh_band(const SurfaceMesh& mesh, const std::vector<FaceId>& host_faces,
                 const IncisionParams& params, SurfaceMesh& refined, EditMaps& maps,
                 std::vector<VertexId>& c, IncisionResult& result) {
  const double L = params.target_edge_length > 0.0 ? params.target_edge_length
                                                   : mean_edge_length(mesh, host_faces);
  // Not band_around: the cut is open even where its two ends happen to be adjacent.
  std::vector<Vec3> trace;
  for (const VertexId v : c) trace.push_back(refined.position(v));
  RemeshParams rp;
  rp.target_edge_length = L;
  rp.region = faces_near_polyline(refined, trace, params.band_width * L);
  rp.grading = params.grading;
  if (params.grading > 1.0) rp.grading_curve = trace;
  rp.constrained_edges = carry_edges(maps, refined, params.constrained_edges);
  for (std::size_t i = 0; i + 1 < c.size(); ++i) rp.constrained_edges.emplace_back(c[i], c[i + 1]);
  rp.constrained_vertices.assign(refined.num_vertices(), false);
  for (std::size_t v = 0; v < refined.num_vertices() && !params.constrained_vertices.empty(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    if (o.parents.size() == 1 && o.parents[0].index() < params.constrained_vertices.size())
      rp.constrained_vertices[v] = params.constrained_vertices[o.parents[0].index()];
  }
  // The cut keeps an inner vertex, so a short slit cannot collapse to one edge (both lips
  // would be that edge, and the slit would close).
  rp.constrained_vertices[c[c.size() / 2].index()] = true;
  rp.passes = params.band_passes;
  CutRemesh best = remesh_keeping_cut(rp, refined, maps, c);
  result.remeshed = true;
  result.band_before = best.before;
  // Again from the raw cut (`refined` is still the traced cut), graded out to the host's
  // spacing: the first of kRepairTargets that lifts the band to the limit, else the best. An
  // attempt that fails leaves the first remesh as it was.
  for (int attempt = 0; attempt < params.repair_attempts; ++attempt) {
    if (!(best.after.min_angle_deg < params.repair_below_deg)) break;
    const double fraction = kRepairTargets[attempt];
    RemeshParams finer = rp;
    finer.target_edge_length = fraction * L;
    finer.grading = std::max(params.grading, 1.5);
    finer.grading_curve = trace;
    try {
      CutRemesh tried = remesh_keeping_cut(finer, refined, maps, c);
      if (tried.after.min_angle_deg > best.after.min_angle_deg) {
        best = std::move(tried);
        result.band_repair_fraction = fraction;
      }
    } catch (const InvalidArgument&) {
    } catch (const Error&) {
    }
  }
  refined = std::move(best.mesh);
  maps = std::move(best.maps);
  c = std::move(best.cut);
  result.band_after = best.after;
}

// An end of the curve within `fraction` of its face's mean edge length from the open boundary
// is put on the boundary (the surgeon drew to the rim): the closest point of the nearest
// boundary edge. Cost O(F) (the boundary half-edges are found by scanning all of them).
void snap_end_to_boundary(const SurfaceMesh& mesh, double fraction, SurfacePoint& p) {
  const auto fv = mesh.face_vertices(p.face);
  double spacing = 0.0;
  for (int k = 0; k < 3; ++k) spacing += (mesh.position(fv[(k + 1) % 3]) - mesh.position(fv[k])).norm() / 3.0;
  double best = fraction * spacing;
  for (std::size_t h = 0; h < 3 * mesh.num_faces(); ++h) {
    if (mesh.twin(HalfedgeId(h)).valid()) continue;
    const Vec3& a = mesh.position(mesh.from_vertex(HalfedgeId(h)));
    const Vec3& b = mesh.position(mesh.to_vertex(HalfedgeId(h)));
    const Vec3 d = b - a;
    const double t = std::clamp((p.position - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double dist = (p.position - (a + t * d)).norm();
    if (!(dist < best)) continue;
    best = dist;
    const int k = static_cast<int>(h % 3);
    p.face = SurfaceMesh::face(HalfedgeId(h));
    p.bary = Eigen::Vector3d::Zero();
    p.bary[k] = 1.0 - t;
    p.bary[(k + 1) % 3] = t;
    p.position = a + t * d;
  }
}

}  // namespace

IncisionResult incise(const SurfaceMesh& mesh, const std::vector<Vec3>& points,
                      const IncisionParams& params) {
  if (points.size() < 2)
    throw InvalidArgument("an incision needs at least 2 points, got " +
                          std::to_string(points.size()));
  if (!(params.max_distance > 0.0)) throw InvalidArgument("max_distance must be > 0");
  if (!(params.target_edge_length >= 0.0)) throw InvalidArgument("target_edge_length must be >= 0");
  if (!(params.end_snap >= 0.0 && params.end_snap <= 0.5))
    throw InvalidArgument("end_snap must be in [0, 0.5]");
  if (!(params.band_width > 0.0 && params.band_width <= 20.0))
    throw InvalidArgument("band_width must be in (0, 20] target edge lengths");
  if (!(params.repair_below_deg >= 0.0 && params.repair_below_deg <= 40.0))
    throw InvalidArgument("repair_below_deg must be in [0, 40] degrees");
  if (params.repair_attempts < 0 || params.repair_attempts > static_cast<int>(std::size(kRepairTargets)))
    throw InvalidArgument("repair_attempts must be in [0, " + std::to_string(std::size(kRepairTargets)) + "]");
  if (!params.constrained_vertices.empty() && params.constrained_vertices.size() != mesh.num_vertices())
    throw InvalidArgument("constrained_vertices: one flag per vertex");
  // Crossings are inserted where the curve is, with or without the band remesh (which removes
  // the slivers): snapping them to vertices by a sliver fraction moved the lips off the curve,
  // and with dense points made the cut revisit a vertex (a false self-crossing).

  std::vector<SurfacePoint> sp;
  std::vector<PathEvent> pe;
  for (std::size_t i = 0; i < points.size(); ++i) {
    sp.push_back(closest_surface_point(mesh, points[i]));
    if (sp.back().distance > params.max_distance)
      throw InvalidArgument("incision point " + std::to_string(i + 1) + " " +
                            detail::point_text(points[i]) + " is off the surface: " +
                            std::to_string(sp.back().distance) + " mm away (limit " +
                            std::to_string(params.max_distance) + " mm)");
    if (params.mode == IncisionMode::CutThroughFaces && (i == 0 || i + 1 == points.size()))
      snap_end_to_boundary(mesh, params.end_snap, sp.back());
    pe.push_back(detail::point_event(mesh, sp.back(), kExactCrossing));
    if (params.mode == IncisionMode::SnapToEdges) {
      // Nearest corner of the face.
      const auto fv = mesh.face_vertices(sp.back().face);
      int k = 0;
      for (int j = 1; j < 3; ++j)
        if (sp.back().bary[j] > sp.back().bary[k]) k = j;
      pe.back() = PathEvent{};
      pe.back().vertex = fv[k];
    }
  }

  IncisionResult result;
  std::optional<detail::TriangleSoup> refining;
  std::vector<int> path;
  int snapped = 0;
  if (params.mode == IncisionMode::SnapToEdges) {
    refining.emplace(mesh);
    auto append = [&](int v) {
      if (path.empty() || path.back() != v) path.push_back(v);
    };
    append(pe[0].vertex.value);
    for (std::size_t i = 1; i < points.size(); ++i)
      for (const VertexId v : detail::shortest_edge_path(mesh, pe[i - 1].vertex, pe[i].vertex))
        append(v.value);
  } else {
    // The whole curve as one chain of events on the original mesh: the points and the exact
    // crossings of each segment's trace with the edges, consecutive duplicates collapsed.
    std::vector<PathEvent> chain{pe[0]};
    auto push = [&](const PathEvent& e) {
      if (!chain.back().same_as(e)) chain.push_back(e);
    };
    for (std::size_t i = 1; i < points.size(); ++i) {
      if (!pe[i - 1].same_as(pe[i]))
        for (const PathEvent& e :
             detail::trace_between(mesh, sp[i - 1], pe[i - 1], sp[i], pe[i], kExactCrossing,
                                   int(i)))
          push(e);
      push(pe[i]);
    }
    // Exactly on the curve, unless that makes a degenerate face (where the curve grazes a
    // vertex, or edges the refinement made from a vertex to earlier cut vertices, within about
    // 1e-5 of an edge): then again, with points and crossings that close to an existing vertex
    // or edge put on it, 1e-6 to 1e-2 of an edge (rare: ~1% of random dense curves).
    const double edge = mesh.mean_edge_length();
    constexpr double kRetrySnaps[] = {0.0, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2};  // of an edge
    constexpr std::size_t kLevels = std::size(kRetrySnaps);
    for (std::size_t level = 0; level < kLevels; ++level) {
      refining.emplace(mesh);
      try {
        CutBuilder builder(mesh, *refining, kRetrySnaps[level] * edge);
        builder.start(chain[0]);
        for (std::size_t k = 1; k < chain.size(); ++k) builder.extend(chain[k - 1], chain[k]);
        path = builder.path();
      } catch (const InvalidArgument&) {
        // Exactly, the curve crosses or touches itself. With snapping, two passes of the curve
        // close to each other may have been merged: snap further.
        if (level == 0 || level + 1 == kLevels) throw;
        continue;
      }
      const int bad = degenerate_face(*refining, mesh.num_faces());
      if (bad < 0) break;
      if (level + 1 == kLevels)
        throw InvalidArgument("the incision cannot be cut without a degenerate triangle near " +
                              detail::point_text(refining->position(refining->face(bad)[0])) +
                              "; move it slightly");
    }
    for (const int v : path)
      if (v < static_cast<int>(mesh.num_vertices())) ++snapped;
  }
  detail::TriangleSoup& soup = *refining;
  result.inserted_vertices = static_cast<int>(soup.num_vertices() - mesh.num_vertices());
  if (path.size() < 2)
    throw InvalidArgument(params.mode == IncisionMode::SnapToEdges
                              ? "the incision is shorter than one mesh edge: its points all "
                                "snap to the vertex at " +
                                    detail::point_text(soup.position(path.front()))
                              : "the incision has no length: its points all lie at " +
                                    detail::point_text(soup.position(path.front())));
  {
    std::set<int> seen;
    for (const int v : path)
      if (!seen.insert(v).second)
        throw InvalidArgument("the incision crosses itself at " + detail::point_text(soup.position(v)));
  }
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
    if (!soup.has_edge(path[i], path[i + 1]))
      throw Error("incise: internal error: consecutive cut vertices are not adjacent");
  // A slit of one edge would re-close (both lips would be the same edge): split it.
  if (path.size() == 2) {
    path.insert(path.begin() + 1, soup.split_edge(path[0], path[1], 0.5));
    ++result.inserted_vertices;
  }

  EditMaps refine_maps;
  SurfaceMesh refined = std::move(soup).build(refine_maps);
  std::vector<VertexId> c;
  for (const int v : path) c.emplace_back(v);
  std::size_t m = c.size() - 1;
  for (std::size_t i = 0; i < m; ++i)
    if (!detail::find_halfedge(refined, c[i], c[i + 1]).valid() ||
        !detail::find_halfedge(refined, c[i + 1], c[i]).valid())
      throw InvalidArgument("the incision runs along the open boundary near " +
                            detail::point_text(refined.position(c[i])));
  for (std::size_t i = 1; i < m; ++i)
    if (refined.is_boundary(c[i]))
      throw InvalidArgument("the incision touches the open boundary at " +
                            detail::point_text(refined.position(c[i])) +
                            " between its ends; end it there or keep it away from the boundary");

  if (params.mode == IncisionMode::CutThroughFaces && params.remesh) {
    std::vector<FaceId> host;
    for (const SurfacePoint& p : sp) host.push_back(p.face);
    remesh_band(mesh, host, params, refined, refine_maps, c, result);
    m = c.size() - 1;
  }

  // Duplicate path vertices: interior path vertices always, ends only on the boundary (an
  // interior end stays shared by both lips: the end of a slit).
  std::vector<FaceIndices> faces = refined.faces();
  std::vector<Vec3> positions = refined.positions();
  EditMaps cut_maps = EditMaps::identity(refined.num_vertices(), refined.num_faces());
  result.starts_on_boundary = refined.is_boundary(c.front());
  result.ends_on_boundary = refined.is_boundary(c.back());
  result.right = c;
  result.left = c;
  for (std::size_t i = 0; i <= m; ++i) {
    if ((i == 0 || i == m) && !refined.is_boundary(c[i])) continue;
    const VertexId copy(positions.size());
    positions.push_back(refined.position(c[i]));
    cut_maps.vertices.push_back(VertexOrigin{VertexOriginKind::Copy, {c[i]}, {1.0}});
    for (const FaceId f : left_wedge(refined, c, i))
      for (auto& corner : faces[f.index()])
        if (corner == c[i].value) corner = copy.value;
    result.left[i] = copy;
  }
  result.mesh = SurfaceMesh(std::move(positions), std::move(faces));
  result.maps = compose(refine_maps, cut_maps);
  result.snapped_points = snapped;
  for (std::size_t i = 0; i < m; ++i)
    result.length += (result.mesh.position(c[i + 1]) - result.mesh.position(c[i])).norm();
  for (const std::size_t i : {std::size_t(0), m}) {
    if (!refined.is_boundary(c[i])) continue;
    for (const VertexId v : {result.left[i], result.right[i]})
      result.open_end_corner_deg =
          std::min(result.open_end_corner_deg.value_or(360.0), vertex_angle_sum_deg(result.mesh, v));
  }
  return result;
}

}  // namespace sutura::engine
