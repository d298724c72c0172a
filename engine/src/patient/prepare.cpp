#include "sutura/engine/patient/prepare.hpp"
#include "sutura/engine/surgery/resect.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "../surgery/cgal_remesh.hpp"
#include "sutura/engine/surgery/remesh.hpp"

namespace sutura::engine {
namespace {

std::string fmt(double v, int precision = 3) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

std::string at(const Vec3& p) {
  // Appended in steps: GCC 12's -Wrestrict misfires on the one-expression form once inlined.
  std::string s = "(";
  s += fmt(p.x(), 4);
  s += ", ";
  s += fmt(p.y(), 4);
  s += ", ";
  s += fmt(p.z(), 4);
  s += ") mm";
  return s;
}

// Faces connected across edges, labelled 0, 1, ... in order of their smallest face; `cut`
// (per half-edge) stops the flood. Returns the label per face and the number of labels.
template <class Cut>
std::pair<std::vector<int>, int> face_groups(const SurfaceMesh& mesh, const Cut& cut) {
  std::vector<int> label(mesh.num_faces(), -1);
  int groups = 0;
  std::vector<int> stack;
  for (std::size_t seed = 0; seed < mesh.num_faces(); ++seed) {
    if (label[seed] >= 0) continue;
    label[seed] = groups;
    stack.assign(1, static_cast<int>(seed));
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const HalfedgeId h = SurfaceMesh::halfedge(FaceId(f), k);
        if (mesh.is_boundary(h) || cut(h)) continue;
        const int g = SurfaceMesh::face(mesh.twin(h)).value;
        if (label[static_cast<std::size_t>(g)] < 0) {
          label[static_cast<std::size_t>(g)] = groups;
          stack.push_back(g);
        }
      }
    }
    ++groups;
  }
  return {label, groups};
}

// The faces listed (in increasing order), vertices renumbered in their old order. Cost
// O(k log k) for k faces.
SurfaceMesh submesh(const SurfaceMesh& mesh, const std::vector<int>& face_list) {
  std::vector<int> used;
  for (const int f : face_list)
    for (const int v : mesh.faces()[static_cast<std::size_t>(f)]) used.push_back(v);
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<Vec3> positions;
  positions.reserve(used.size());
  for (const int v : used) positions.push_back(mesh.positions()[static_cast<std::size_t>(v)]);
  const auto index = [&](int v) {
    return static_cast<int>(std::lower_bound(used.begin(), used.end(), v) - used.begin());
  };
  std::vector<FaceIndices> faces;
  faces.reserve(face_list.size());
  for (const int f : face_list) {
    const FaceIndices& t = mesh.faces()[static_cast<std::size_t>(f)];
    faces.push_back({index(t[0]), index(t[1]), index(t[2])});
  }
  return SurfaceMesh(std::move(positions), std::move(faces));
}

SurfaceMesh submesh(const SurfaceMesh& mesh, const std::vector<bool>& keep) {
  std::vector<int> face_list;
  for (std::size_t f = 0; f < keep.size(); ++f)
    if (keep[f]) face_list.push_back(static_cast<int>(f));
  return submesh(mesh, face_list);
}

// Newell's normal of a closed polygon (not normalised): |n| is twice its area.
Vec3 newell(const std::vector<Vec3>& loop) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < loop.size(); ++i) n += loop[i].cross(loop[(i + 1) % loop.size()]);
  return n;
}

std::vector<Vec3> loop_points(const SurfaceMesh& mesh, const std::vector<VertexId>& loop) {
  std::vector<Vec3> p;
  p.reserve(loop.size());
  for (const VertexId v : loop) p.push_back(mesh.position(v));
  return p;
}

// Six times the volume enclosed by the mesh with every boundary loop closed by a fan around
// its centroid; positive when the faces are oriented outward.
double enclosed_volume6(const SurfaceMesh& mesh) {
  const Vec3 o = mesh.bounds().center();  // a fixed origin keeps the sum well conditioned
  double v = 0.0;
  for (const FaceIndices& f : mesh.faces()) {
    const Vec3 a = mesh.positions()[f[0]] - o, b = mesh.positions()[f[1]] - o, c = mesh.positions()[f[2]] - o;
    v += a.dot(b.cross(c));
  }
  for (const auto& loop : mesh.boundary_loops()) {
    const std::vector<Vec3> p = loop_points(mesh, loop);
    Vec3 c = Vec3::Zero();
    for (const Vec3& q : p) c += q;
    c /= static_cast<double>(p.size());
    // Boundary half-edges run with the mesh on their left; the closing fan runs against them.
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 a = c - o, b = p[(i + 1) % p.size()] - o, d = p[i] - o;
      v += a.dot(b.cross(d));
    }
  }
  return v;
}

struct Plane {
  Vec3 centre, normal;
  double radius = 0.0, flatness = 0.0;
};

// The plane of a closed polyline: its centre is the centroid of the polyline as a wire (edges
// weighted by length, so uneven spacing does not pull it aside), its normal Newell's (out of
// the mesh for a boundary loop), its radius the mean distance of the wire from the centre, and
// its flatness the largest distance of a point from the plane.
Plane loop_plane(const std::vector<Vec3>& p) {
  Plane plane;
  plane.centre = Vec3::Zero();
  double length = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3& a = p[i];
    const Vec3& b = p[(i + 1) % p.size()];
    const double l = (b - a).norm();
    plane.centre += 0.5 * l * (a + b);
    length += l;
  }
  plane.centre /= length;
  std::vector<Vec3> centred;
  for (const Vec3& q : p) centred.push_back(q - plane.centre);
  plane.normal = -newell(centred).normalized();  // boundary direction: mesh on the left
  for (std::size_t i = 0; i < centred.size(); ++i) {
    const Vec3& a = centred[i];
    const Vec3& b = centred[(i + 1) % centred.size()];
    const double l = (b - a).norm();
    const double ha = a.dot(plane.normal), hb = b.dot(plane.normal);
    plane.radius += 0.5 * l * ((a - ha * plane.normal).norm() + (b - hb * plane.normal).norm());
    plane.flatness = std::max(plane.flatness, std::abs(ha));
  }
  plane.radius /= length;
  return plane;
}

struct Cap {
  std::vector<int> faces;
  Plane plane;
};

// Flat end caps: groups of faces bounded by creases (dihedral angle above the crease angle)
// that are flat discs of a reasonable size. The group of largest area is the vessel wall.
std::vector<Cap> find_caps(const SurfaceMesh& mesh, double crease_angle_deg) {
  const std::size_t F = mesh.num_faces();
  std::vector<Vec3> normal(F);
  for (std::size_t f = 0; f < F; ++f) normal[f] = mesh.face_normal(FaceId(static_cast<int>(f)));
  const double crease_cos = std::cos(crease_angle_deg * std::numbers::pi / 180.0);
  const auto crease = [&](HalfedgeId h) {
    const auto f = static_cast<std::size_t>(SurfaceMesh::face(h).value);
    const auto g = static_cast<std::size_t>(SurfaceMesh::face(mesh.twin(h)).value);
    return normal[f].dot(normal[g]) < crease_cos;
  };
  const auto [label, groups] = face_groups(mesh, crease);
  std::vector<double> area(static_cast<std::size_t>(groups), 0.0);
  std::vector<std::vector<int>> members(static_cast<std::size_t>(groups));
  for (std::size_t f = 0; f < F; ++f) {
    area[static_cast<std::size_t>(label[f])] += mesh.face_area(FaceId(static_cast<int>(f)));
    members[static_cast<std::size_t>(label[f])].push_back(static_cast<int>(f));
  }
  const auto wall = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
  const double mean_edge = mesh.mean_edge_length();
  const double flat_cos = std::cos(30.0 * std::numbers::pi / 180.0);
  std::vector<Cap> caps;
  for (int g = 0; g < groups; ++g) {
    if (g == wall) continue;
    const auto& fs = members[static_cast<std::size_t>(g)];
    const double A = area[static_cast<std::size_t>(g)];
    const double equivalent_radius = std::sqrt(A / std::numbers::pi);
    if (!(equivalent_radius >= 2.0 * mean_edge)) continue;  // a noise facet, not an end
    // A disc: its faces as a mesh of their own have one boundary loop and Euler characteristic 1.
    SurfaceMesh piece;
    try {
      piece = submesh(mesh, fs);
    } catch (const TopologyError&) {
      continue;  // pinched: not a disc
    }
    const auto loops = piece.boundary_loops();
    if (loops.size() != 1 || piece.euler_characteristic() != 1 || loops[0].size() < 8) continue;
    Vec3 n = Vec3::Zero(), c = Vec3::Zero();
    for (const int f : fs) {
      const double a = mesh.face_area(FaceId(f));
      n += a * normal[static_cast<std::size_t>(f)];
      c += a * mesh.face_centroid(FaceId(f));
    }
    if (n.norm() == 0.0) continue;
    n.normalize();
    c /= A;
    bool flat = true;
    for (const int f : fs) flat = flat && normal[static_cast<std::size_t>(f)].dot(n) >= flat_cos;
    // The rim as the wall's boundary once the cap is gone: the cap's loop runs the other way.
    std::vector<Vec3> rim = loop_points(piece, loops[0]);
    std::reverse(rim.begin(), rim.end());
    Plane plane = loop_plane(rim);
    for (const Vec3& q : piece.positions())
      flat = flat && std::abs((q - c).dot(n)) <= 0.1 * equivalent_radius;
    if (!flat) continue;
    caps.push_back({fs, plane});
  }
  return caps;
}

// Taubin's lambda|mu smoothing with uniform (umbrella) weights; held vertices stay.
void taubin_smooth(std::vector<Vec3>& x, const SurfaceMesh& mesh, const std::vector<bool>& held,
                   int iterations) {
  const std::size_t V = x.size();
  std::vector<int> start(V + 1, 0), adj;
  const auto edges = mesh.edges();
  for (const HalfedgeId h : edges) {
    ++start[static_cast<std::size_t>(mesh.from_vertex(h).value) + 1];
    ++start[static_cast<std::size_t>(mesh.to_vertex(h).value) + 1];
  }
  for (std::size_t v = 0; v < V; ++v) start[v + 1] += start[v];
  adj.resize(static_cast<std::size_t>(start[V]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const HalfedgeId h : edges) {
    const int a = mesh.from_vertex(h).value, b = mesh.to_vertex(h).value;
    adj[static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++)] = b;
    adj[static_cast<std::size_t>(fill[static_cast<std::size_t>(b)]++)] = a;
  }
  std::vector<Vec3> next(V);
  for (int it = 0; it < iterations; ++it)
    for (const double factor : {0.5, -0.53}) {
      for (std::size_t v = 0; v < V; ++v) {
        next[v] = x[v];
        const int n = start[v + 1] - start[v];
        if (held[v] || n == 0) continue;
        Vec3 mean = Vec3::Zero();
        for (int k = start[v]; k < start[v + 1]; ++k) mean += x[static_cast<std::size_t>(adj[static_cast<std::size_t>(k)])];
        next[v] = x[v] + factor * (mean / n - x[v]);
      }
      x.swap(next);
    }
}

}  // namespace

PrepareResult prepare_vessel(const SurfaceMesh& input, const PrepareParams& params) {
  if (input.empty()) throw InvalidArgument("prepare: the surface has no faces");
  if (input.num_faces() > kMaxPrepareInputFaces)
    throw PrepareError(PrepareError::Kind::TooLarge,
                       "prepare: the surface has " + std::to_string(input.num_faces()) +
                           " faces, more than the " + std::to_string(kMaxPrepareInputFaces) +
                           " prepare takes; export the segmentation coarser");
  if (params.edge_length && !(*params.edge_length > 0.0 && std::isfinite(*params.edge_length)))
    throw PrepareError(PrepareError::Kind::EdgeLength,
                       "prepare: the edge length must be a positive number of mm, not " +
                           fmt(*params.edge_length));
  if (params.smoothing_iterations < 0 || params.smoothing_iterations > 1000)
    throw InvalidArgument("prepare: smoothing iterations must be in [0, 1000]");
  if (!(params.smoothing_bound >= 0.0 && params.smoothing_bound <= 1.0))
    throw InvalidArgument("prepare: the smoothing bound must be in [0, 1] target edge lengths");
  if (params.remesh_iterations < 1 || params.remesh_iterations > 100)
    throw InvalidArgument("prepare: remeshing iterations must be in [1, 100]");
  if (!(params.drop_area_fraction > 0.0 && params.drop_area_fraction < 1.0))
    throw InvalidArgument("prepare: the drop area fraction must be in (0, 1)");
  if (!(params.crease_angle_deg >= 10.0 && params.crease_angle_deg <= 80.0))
    throw InvalidArgument("prepare: the crease angle must be in [10, 80] degrees");

  PrepareResult result;
  auto clock = std::chrono::steady_clock::now();
  const auto step_done = [&](const char* step) {
    const auto now = std::chrono::steady_clock::now();
    result.step_seconds.emplace_back(step, std::chrono::duration<double>(now - clock).count());
    clock = now;
  };
  result.input_vertices = input.num_vertices();
  result.input_faces = input.num_faces();

  // 0. The user's clip planes: each a resection beyond one plane.
  SurfaceMesh clipped_input;
  if (!params.clips.empty()) clipped_input = input;
  for (std::size_t k = 0; k < params.clips.size(); ++k) {
    const PrepareClip& clip = params.clips[k];
    std::string which = "prepare: clip plane ";
    which += std::to_string(k + 1);
    which += " at ";
    which += at(clip.origin);
    if (!(clip.normal.allFinite() && clip.normal.norm() > 0.0 && clip.origin.allFinite() && clip.radius > 0.0 &&
          std::isfinite(clip.radius)))
      throw PrepareError(PrepareError::Kind::Clip, which + ": needs a finite origin, a non-zero normal and a positive radius");
    const Vec3 n = clip.normal.normalized();
    // The seed: the vertex farthest beyond the plane within the radius.
    std::optional<Vec3> seed;
    double beyond = 0.0;
    for (const Vec3& p : clipped_input.positions())
      if ((p - clip.origin).norm() <= clip.radius && (p - clip.origin).dot(n) > beyond)
        beyond = (p - clip.origin).dot(n), seed = p;
    if (!seed)
      throw PrepareError(PrepareError::Kind::Clip, which + ": no part of the surface within " + fmt(clip.radius) +
                                                       " mm of the origin lies on the side the normal points to");
    ResectionParams rp;
    rp.radius = clip.radius;
    try {
      ResectionResult r = resect(clipped_input, {CutPlane{clip.origin, n}}, *seed, rp);
      result.clipped.emplace_back(r.removed_faces, r.removed_area);
      clipped_input = std::move(r.mesh);
    } catch (const InvalidArgument& e) {
      throw PrepareError(PrepareError::Kind::Clip, which + ": " + e.what());
    }
  }
  const SurfaceMesh& source = params.clips.empty() ? input : clipped_input;
  if (!params.clips.empty()) step_done("clipping");

  // 1. The largest component; the others are dropped if small, refused if not.
  const auto [component, components] = face_groups(source, [](HalfedgeId) { return false; });
  std::vector<double> area(static_cast<std::size_t>(components), 0.0);
  std::vector<Vec3> centroid(static_cast<std::size_t>(components), Vec3::Zero());
  std::vector<std::size_t> count(static_cast<std::size_t>(components), 0);
  for (std::size_t f = 0; f < source.num_faces(); ++f) {
    const auto c = static_cast<std::size_t>(component[f]);
    const double a = source.face_area(FaceId(static_cast<int>(f)));
    area[c] += a;
    centroid[c] += a * source.face_centroid(FaceId(static_cast<int>(f)));
    ++count[c];
  }
  const auto largest = static_cast<int>(std::max_element(area.begin(), area.end()) - area.begin());
  std::vector<int> order;
  for (int c = 0; c < components; ++c)
    if (c != largest) order.push_back(c);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });
  for (const int c : order) {
    const auto k = static_cast<std::size_t>(c);
    const Vec3 at_c = area[k] > 0.0 ? Vec3(centroid[k] / area[k]) : Vec3::Zero();
    if (area[k] >= params.drop_area_fraction * area[static_cast<std::size_t>(largest)])
      throw PrepareError(
          PrepareError::Kind::SeveralComponents,
          "prepare: the surface has several large components: besides the largest (" +
              std::to_string(count[static_cast<std::size_t>(largest)]) + " faces, " +
              fmt(area[static_cast<std::size_t>(largest)], 4) + " mm^2), one of " +
              std::to_string(count[k]) + " faces and " + fmt(area[k], 4) + " mm^2 around " +
              at(at_c) + " (more than " + fmt(100.0 * params.drop_area_fraction) +
              " % of the largest); export the vessel alone, or remove the others");
    result.dropped.push_back({count[k], area[k], at_c});
  }
  std::vector<bool> keep(source.num_faces());
  for (std::size_t f = 0; f < keep.size(); ++f) keep[f] = component[f] == largest;
  SurfaceMesh vessel = components == 1 ? source : submesh(source, keep);

  step_done("components");
  // Crossing faces make every later step meaningless (which side is the lumen?).
  const auto crossings = self_intersections(vessel, 100);
  if (!crossings.empty()) {
    const Vec3 where = vessel.face_centroid(crossings.front().first);
    throw PrepareError(PrepareError::Kind::SelfIntersecting,
                       "prepare: the surface intersects itself: " +
                           std::string(crossings.size() >= 100 ? "at least " : "") +
                           std::to_string(crossings.size()) + " pairs of crossing faces, the first near " +
                           at(where) + "; repair the segmentation before preparing it");
  }

  step_done("self_intersections");
  // 2. Outward orientation.
  if (enclosed_volume6(vessel) < 0.0) {
    std::vector<FaceIndices> faces = vessel.faces();
    for (FaceIndices& f : faces) std::swap(f[1], f[2]);
    vessel = SurfaceMesh(vessel.positions(), std::move(faces));
    result.flipped = true;
  }

  // 3. Open ends already in the input must be flat; flat caps are found and opened.
  std::vector<PreparedEnd> ends;
  for (const auto& loop : vessel.boundary_loops()) {
    const Plane plane = loop_plane(loop_points(vessel, loop));
    if (!(plane.flatness <= 0.1 * plane.radius))
      throw PrepareError(PrepareError::Kind::OpenHole,
                         "prepare: the surface has a hole that is not a flat open end: a boundary "
                         "loop of " + std::to_string(loop.size()) + " vertices around " +
                             at(plane.centre) + ", radius " + fmt(plane.radius) + " mm, strays " +
                             fmt(plane.flatness) + " mm from its plane (at most 10 % of the "
                             "radius); close it in the segmentation tool or cut the end flat");
    // The wall meets an end at about a right angle; around a hole cut into the wall it lies
    // in the hole's plane.
    double along = 0.0;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const HalfedgeId h = vessel.vertex_halfedge(loop[i]);  // the outgoing boundary half-edge
      along += std::abs(vessel.face_normal(SurfaceMesh::face(h)).dot(plane.normal));
    }
    along /= static_cast<double>(loop.size());
    if (!(along <= 0.5))
      throw PrepareError(PrepareError::Kind::OpenHole,
                         "prepare: the surface has a hole in its wall, not at a vessel end: a "
                         "boundary loop of " + std::to_string(loop.size()) + " vertices around " +
                             at(plane.centre) + ", radius " + fmt(plane.radius) +
                             " mm, lies in the wall's own plane; close it in the segmentation tool");
    ends.push_back({{"", plane.centre, plane.normal, plane.radius}, false, 0, plane.flatness});
  }
  const std::vector<Cap> caps = find_caps(vessel, params.crease_angle_deg);
  for (const Cap& cap : caps)
    ends.push_back({{"", cap.plane.centre, cap.plane.normal, cap.plane.radius}, true,
                    cap.faces.size(), cap.plane.flatness});
  if (ends.empty())
    throw PrepareError(PrepareError::Kind::NoEnds,
                       "prepare: no flat end caps were found (faces meeting at more than " +
                           fmt(params.crease_angle_deg) + " degrees around a flat disc) and the "
                           "surface has no open ends; a vessel needs at least one end");
  std::stable_sort(ends.begin(), ends.end(),
                   [](const PreparedEnd& a, const PreparedEnd& b) { return a.end.radius > b.end.radius; });
  for (std::size_t i = 0; i < ends.size(); ++i) ends[i].end.name = "end_" + std::to_string(i + 1);

  // The target edge length, and whether it suits the narrowest end.
  const double r_min = ends.back().end.radius;
  const double derived = 2.0 * std::numbers::pi * r_min / 16.0;
  const double h = params.edge_length.value_or(derived);
  result.edge_length = h;
  result.edge_length_derived = !params.edge_length.has_value();
  const double h_lo = 2.0 * std::numbers::pi * r_min / 64.0, h_hi = 2.0 * std::numbers::pi * r_min / 6.0;
  if (h < h_lo * (1.0 - 1e-12) || h > h_hi * (1.0 + 1e-12))
    throw PrepareError(PrepareError::Kind::EdgeLength,
                       "prepare: an edge length of " + fmt(h) + " mm is out of range for this "
                       "vessel: its narrowest end (" + ends.back().end.name + ", radius " +
                           fmt(r_min) + " mm) needs between 6 and 64 edges around it, so between " +
                           fmt(h_lo) + " and " + fmt(h_hi) + " mm");
  const double expected_faces = vessel.total_area() / (std::sqrt(3.0) / 4.0 * h * h);
  if (expected_faces > static_cast<double>(params.max_faces))
    throw PrepareError(PrepareError::Kind::TooLarge,
                       "prepare: an edge length of " + fmt(h) + " mm would give about " +
                           fmt(expected_faces, 3) + " faces, more than the " +
                           std::to_string(params.max_faces) + " allowed");

  // Open the caps; their rims are held by the smoothing (and stay sharp with keep_caps).
  std::vector<bool> is_cap(vessel.num_faces(), false);
  for (const Cap& cap : caps)
    for (const int f : cap.faces) is_cap[static_cast<std::size_t>(f)] = true;
  std::vector<bool> on_rim(vessel.num_vertices(), false);
  std::vector<std::pair<int, int>> rim_edges;
  for (const HalfedgeId e : vessel.edges()) {
    if (vessel.is_boundary(e)) continue;
    if (is_cap[static_cast<std::size_t>(SurfaceMesh::face(e).value)] !=
        is_cap[static_cast<std::size_t>(SurfaceMesh::face(vessel.twin(e)).value)]) {
      on_rim[static_cast<std::size_t>(vessel.from_vertex(e).value)] = true;
      on_rim[static_cast<std::size_t>(vessel.to_vertex(e).value)] = true;
      rim_edges.emplace_back(vessel.from_vertex(e).value, vessel.to_vertex(e).value);
    }
  }
  SurfaceMesh opened = vessel;
  if (!params.keep_caps && !caps.empty()) {
    std::vector<bool> wall(vessel.num_faces());
    for (std::size_t f = 0; f < wall.size(); ++f) wall[f] = !is_cap[f];
    try {
      opened = submesh(vessel, wall);
    } catch (const TopologyError& e) {
      throw PrepareError(PrepareError::Kind::Topology,
                         std::string("prepare: opening the caps leaves a surface that is not a "
                                     "manifold (two caps touch?): ") + e.what());
    }
    rim_edges.clear();
  }
  const SurfaceMesh reference = opened;  // the input without its caps: the Hausdorff target

  step_done("ends");
  // 4. Smoothing: open ends (projected onto their planes first) and cap rims are held.
  std::vector<Vec3> x = opened.positions();
  std::vector<bool> held(x.size(), false);
  if (params.keep_caps) {
    for (std::size_t v = 0; v < x.size(); ++v) held[v] = on_rim[v];
  }
  for (const auto& loop : opened.boundary_loops()) {
    const Plane plane = loop_plane(loop_points(opened, loop));
    for (const VertexId v : loop) {
      Vec3& p = x[v.index()];
      p -= (p - plane.centre).dot(plane.normal) * plane.normal;
      held[v.index()] = true;
    }
  }
  const std::vector<Vec3> unsmoothed = x;
  taubin_smooth(x, opened, held, params.smoothing_iterations);
  // Smoothing takes off noise, not shape: no vertex moves farther than the bound (a coarctation's
  // shoulder, whose curvature radius can be below a millimetre, would otherwise be worn down).
  const double bound = params.smoothing_bound * h;
  for (std::size_t v = 0; v < x.size(); ++v) {
    const Vec3 d = x[v] - unsmoothed[v];
    if (d.norm() > bound) x[v] = unsmoothed[v] + d * (bound / d.norm());
  }

  step_done("smoothing");
  // 5. Isotropic remeshing onto the smoothed surface.
  detail::CgalRemeshInput in;
  in.positions = &x;
  in.faces = &opened.faces();
  in.region.assign(opened.num_faces(), true);
  in.bands = {{h, -1.0}};
  in.iterations = params.remesh_iterations;
  in.constrained_edges = rim_edges;
  // 3 % of the target: with the noise and the smoothing's bounded moves, the distance to the
  // input stays below a tenth of it.
  in.max_deviation = 0.03 * h;
  in.repair_below_deg = 27.0;
  in.coarsen_below = 0.5 * h;
  in.coarsen_in_halves_from = params.coarsen_in_halves_from;
  detail::CgalRemeshOutput out = detail::cgal_remesh(in);
  result.vessel = SurfaceMesh(std::move(out.positions), std::move(out.faces));
  if (result.vessel.num_faces() > params.max_faces)
    throw PrepareError(PrepareError::Kind::TooLarge,
                       "prepare: the remeshed vessel has " + std::to_string(result.vessel.num_faces()) +
                           " faces (finer where the wall bends fast), more than the " +
                           std::to_string(params.max_faces) + " allowed; give a longer --edge-length");

  step_done("remeshing");
  // The ends as the remeshed loops show them: each end takes the loop nearest its centre.
  std::vector<Plane> loops;
  for (const auto& loop : result.vessel.boundary_loops())
    loops.push_back(loop_plane(loop_points(result.vessel, loop)));
  for (PreparedEnd& end : ends) {
    if (params.keep_caps && end.was_cap) continue;
    const Plane* nearest = nullptr;
    for (const Plane& plane : loops)
      if (!nearest || (plane.centre - end.end.centre).norm() < (nearest->centre - end.end.centre).norm())
        nearest = &plane;
    if (!nearest) continue;
    end.end.centre = nearest->centre;
    end.end.normal = nearest->normal;
    end.end.radius = nearest->radius;
    end.flatness = nearest->flatness;
  }
  result.ends = std::move(ends);

  // 6. Quality and distance to the input.
  const MeshQuality quality = mesh_quality(result.vessel, {});
  result.min_angle_deg = quality.min_angle_deg;
  result.min_edge = quality.min_edge;
  result.max_edge = quality.max_edge;
  result.mean_edge = result.vessel.mean_edge_length();
  // Samples h / 5 apart (the one-sided maxima are short of the true ones by at most that),
  // wider where the samples would pass 16M: each face takes (n + 1)(n + 2) / 2 for n =
  // ceil(longest edge / spacing), and an input face smaller than the spacing 3.
  const auto samples = [&](double spacing) {
    double total = 0.0;
    for (const SurfaceMesh* m : {static_cast<const SurfaceMesh*>(&result.vessel), &reference})
      for (const FaceIndices& f : m->faces()) {
        double longest = 0.0;
        for (int k = 0; k < 3; ++k)
          longest = std::max(longest, (m->positions()[f[k]] - m->positions()[f[(k + 1) % 3]]).norm());
        const double n = std::max(1.0, std::ceil(longest / spacing));
        total += 0.5 * (n + 1.0) * (n + 2.0);
      }
    return total;
  };
  result.hausdorff_spacing = h / 5.0;
  for (int widen = 0; widen < 20 && samples(result.hausdorff_spacing) > 1.6e7; ++widen)
    result.hausdorff_spacing *= 1.5;
  result.to_input = hausdorff_distance(result.vessel, reference, result.hausdorff_spacing);
  step_done("measuring");
  return result;
}

}  // namespace sutura::engine
