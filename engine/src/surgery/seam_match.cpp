#include "sutura/engine/surgery/seam_match.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sutura/engine/errors.hpp"
#include "mesh_walk.hpp"
#include "triangle_soup.hpp"

namespace sutura::engine {

namespace {

// The chain's vertices as a path, a loop's first vertex repeated at the end.
std::vector<int> path_of(const BoundaryChain& c) {
  std::vector<int> p;
  for (const VertexId v : c.vertices) p.push_back(v.value);
  if (c.closed) p.push_back(p.front());
  return p;
}

// Inserts the points at equal arc lengths along `path` (soup vertex ids) into the soup and
// returns them, ends included; `full` receives the path with them inserted. An existing
// vertex within a millionth of a segment of a target point is taken as it is.
std::vector<int> resample_path(detail::TriangleSoup& soup, const std::vector<int>& path,
                               const std::vector<double>& at, std::vector<int>& full) {
  std::vector<double> s(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i)
    s[i] = s[i - 1] + (soup.position(path[i]) - soup.position(path[i - 1])).norm();
  const double length = s.back();
  const double eps = 1e-9 * length;
  std::vector<int> out{path.front()};
  full.assign(1, path.front());
  std::size_t i = 0;            // the target lies on path edge (i, i + 1)
  int last = path.front();      // the last vertex on that edge so far
  double s_last = 0.0;
  for (const double fraction : at) {
    const double target = length * fraction;
    while (i + 2 < path.size() && s[i + 1] <= target) {
      ++i;
      last = path[i];
      s_last = s[i];
      full.push_back(last);
    }
    if (target - s_last <= eps) {
      out.push_back(last);  // an existing vertex (an end of the edge, or an inserted one)
    } else if (s[i + 1] - target <= eps) {
      out.push_back(path[i + 1]);
    } else {
      const double t = (target - s_last) / (s[i + 1] - s_last);
      last = soup.split_edge(last, path[i + 1], t);
      s_last = target;
      out.push_back(last);
      full.push_back(last);
    }
  }
  for (std::size_t j = i + 1; j < path.size(); ++j) full.push_back(path[j]);
  out.push_back(path.back());
  for (std::size_t k = 1; k < out.size(); ++k)
    if (out[k] == out[k - 1])
      throw InvalidArgument("resample_chains: two points within " + std::to_string(eps) +
                            " mm of one vertex of a chain of " + std::to_string(length) + " mm");
  return out;
}

}  // namespace

ResampleChainsResult resample_chains(const SurfaceMesh& mesh, const std::vector<ChainResample>& chains,
                                     const ResampleChainsParams& params) {
  if (!(params.target_edge_length > 0.0) || !std::isfinite(params.target_edge_length))
    throw InvalidArgument("resample_chains: target_edge_length must be > 0");
  if (chains.empty()) throw InvalidArgument("resample_chains: no chain");
  for (std::size_t c = 0; c < chains.size(); ++c) {
    const ChainResample& r = chains[c];
    const std::size_t n = r.chain.vertices.size();
    bool ordered = r.at.size() <= 1000000 && r.at.size() >= (r.chain.closed ? 2u : 0u);
    for (std::size_t k = 0; k < r.at.size() && ordered; ++k)
      ordered = r.at[k] > 0.0 && r.at[k] < 1.0 && (k == 0 || r.at[k] > r.at[k - 1]);
    if (!ordered)
      throw InvalidArgument("resample_chains: chain " + std::to_string(c + 1) +
                            ": the fractions must increase in (0, 1) (a loop needs two)");
    if (n < 2) throw InvalidArgument("resample_chains: chain " + std::to_string(c + 1) + " has no edge");
    for (std::size_t i = 0; i + (r.chain.closed ? 0 : 1) < n; ++i) {
      const VertexId u = r.chain.vertices[i], w = r.chain.vertices[(i + 1) % n];
      const HalfedgeId h = u.index() < mesh.num_vertices() && w.index() < mesh.num_vertices()
                               ? detail::find_halfedge(mesh, u, w)
                               : HalfedgeId();
      if (!h.valid() || !mesh.is_boundary(h))
        throw InvalidArgument("resample_chains: chain " + std::to_string(c + 1) +
                              " is not a run of boundary edges in the boundary direction");
    }
  }

  detail::TriangleSoup soup(mesh);
  std::vector<std::vector<int>> points;
  std::vector<std::vector<VertexId>> lines;  // the chains with the new points in them
  for (const ChainResample& r : chains) {
    std::vector<int> full;
    points.push_back(resample_path(soup, path_of(r.chain), r.at, full));
    lines.emplace_back(full.begin(), full.end());
    if (r.chain.closed) lines.back().pop_back();
  }
  EditMaps split_maps;
  const SurfaceMesh split = std::move(soup).build(split_maps);

  double band_width = params.band_width;
  std::vector<Vec3> curve;
  if (params.grading > 1.0) {
    // Wide enough for the bands from the target length to the spacing around the chains.
    const double around = band_around(split, lines, 0.0).target_edge_length;
    const double ratio = std::max(around, params.target_edge_length) /
                         std::min(around, params.target_edge_length);
    band_width += 2.0 * std::ceil(std::log(ratio) / std::log(params.grading));
    for (const auto& line : lines)
      for (const VertexId v : line) curve.push_back(split.position(v));
  }
  RemeshParams rp = band_around(split, lines, band_width, params.target_edge_length);
  rp.passes = params.band_passes;
  std::vector<bool> frozen_vertex(split.num_vertices(), false);
  if (!params.frozen_faces.empty()) {
    if (params.frozen_faces.size() != mesh.num_faces())
      throw InvalidArgument("resample_chains: frozen_faces has the wrong size");
    std::vector<FaceId> region;
    for (const FaceId f : *rp.region) {
      if (params.frozen_faces[split_maps.faces[f.index()].parent.index()]) {
        for (const auto v : split.faces()[f.index()]) frozen_vertex[std::size_t(v)] = true;
      } else {
        region.push_back(f);
      }
    }
    if (region.empty()) throw InvalidArgument("resample_chains: every face beside the chains is frozen");
    rp.region = std::move(region);
  }
  rp.grading = params.grading;
  rp.grading_curve = std::move(curve);
  const auto carried = carry_edges(split_maps, split, params.constrained_edges);
  rp.constrained_edges.insert(rp.constrained_edges.end(), carried.begin(), carried.end());
  rp.constrained_vertices.assign(split.num_vertices(), false);
  if (!params.constrained_vertices.empty()) {
    if (params.constrained_vertices.size() != mesh.num_vertices())
      throw InvalidArgument("resample_chains: constrained_vertices has the wrong size");
    for (std::size_t v = 0; v < split.num_vertices(); ++v) {
      const VertexOrigin& o = split_maps.vertices[v];
      if (o.parents.size() == 1) rp.constrained_vertices[v] = params.constrained_vertices[o.parents[0].index()];
    }
  }
  // The old chain vertices go (collapsed along the chain into a neighbour), the new points
  // stay.
  rp.removed_boundary_vertices.assign(split.num_vertices(), false);
  for (const auto& line : lines)
    for (const VertexId v : line) rp.removed_boundary_vertices[v.index()] = true;
  for (const auto& p : points)
    for (const int v : p) rp.constrained_vertices[std::size_t(v)] = true;
  for (std::size_t v = 0; v < split.num_vertices(); ++v)
    if (frozen_vertex[v]) rp.constrained_vertices[v] = true, rp.removed_boundary_vertices[v] = false;
  RemeshResult r = remesh(split, rp);

  std::vector<VertexId> image(split.num_vertices());
  for (std::size_t v = 0; v < r.maps.vertices.size(); ++v) {
    const VertexOrigin& o = r.maps.vertices[v];
    if (o.kind == VertexOriginKind::Copy) image[o.parents[0].index()] = VertexId(v);
  }
  ResampleChainsResult result;
  for (std::size_t c = 0; c < chains.size(); ++c) {
    const auto& p = points[c];
    for (const int v : p)
      if (!image[std::size_t(v)].valid())
        throw Error("resample_chains: internal error: the remesh removed a held chain vertex");
    BoundaryChain out;
    out.closed = chains[c].chain.closed;
    // Point by point: the remesh may leave an old chain vertex between two new ones (it
    // collapses them only when an edge is short enough); the chain then keeps it.
    for (std::size_t k = 0; k + 1 < p.size(); ++k) {
      const BoundaryChain piece = boundary_chain(r.mesh, image[std::size_t(p[k])], image[std::size_t(p[k + 1])]);
      out.vertices.insert(out.vertices.end(), piece.vertices.begin(), piece.vertices.end() - 1);
    }
    if (!out.closed) out.vertices.push_back(image[std::size_t(p.back())]);
    result.chains.push_back(std::move(out));
  }
  result.maps = compose(split_maps, r.maps);
  result.mesh = std::move(r.mesh);
  result.before = r.before;
  result.after = r.after;
  return result;
}

std::vector<double> equal_fractions(int segments) {
  std::vector<double> at;
  for (int k = 1; k < segments; ++k) at.push_back(double(k) / segments);
  return at;
}

double seam_spacing(const SurfaceMesh& mesh, const SuturePair& pair, double min_spacing) {
  const RemeshParams p = band_around(mesh, {pair.a.vertices, pair.b.vertices}, 0.0);
  return std::max(p.target_edge_length, min_spacing);
}

int seam_segments(const SuturePair& pair, double length_a, double length_b, double spacing) {
  const long n = std::lround(0.5 * (length_a + length_b) / spacing);
  return static_cast<int>(std::clamp<long>(n, pair.a.closed ? 3 : 1, 1000000));
}

namespace {

// A chain's length along it as the seams are spaced, at each vertex and at the end (a loop:
// from its first vertex round to it again; n + 1 entries), and the same in current length.
struct ChainMeasure {
  std::vector<double> spaced, current;
  double length() const { return spaced.back(); }
  // The fraction of the spaced length at vertex i (i = n: the end).
  double fraction(std::size_t i) const { return spaced[i] / spaced.back(); }
  // A fraction of the spaced length as a fraction of the current length (piecewise linear
  // between the vertices: exact at each of them).
  double to_current(double x) const {
    const double s = x * spaced.back();
    const std::size_t i = std::min<std::size_t>(
        std::upper_bound(spaced.begin(), spaced.end(), s) - spaced.begin(), spaced.size() - 1);
    const double t = std::clamp((s - spaced[i - 1]) / (spaced[i] - spaced[i - 1]), 0.0, 1.0);
    return (current[i - 1] + t * (current[i] - current[i - 1])) / current.back();
  }
};

ChainMeasure chain_measure(const SurfaceMesh& mesh, const BoundaryChain& c, const std::vector<bool>& frozen,
                           const std::vector<std::array<double, 3>>& rest) {
  const std::size_t n = c.vertices.size();
  const std::size_t edges = c.closed ? n : n - 1;
  ChainMeasure m{std::vector<double>(edges + 1, 0.0), std::vector<double>(edges + 1, 0.0)};
  for (std::size_t i = 0; i < edges; ++i) {
    const VertexId u = c.vertices[i], w = c.vertices[(i + 1) % n];
    const double now = (mesh.position(w) - mesh.position(u)).norm();
    double spaced = now;
    const HalfedgeId h = rest.empty() ? HalfedgeId() : detail::find_halfedge(mesh, u, w);
    if (h.valid() && frozen[SurfaceMesh::face(h).index()]) {
      const FaceId f = SurfaceMesh::face(h);
      const auto& corners = mesh.faces()[f.index()];
      for (int k = 0; k < 3; ++k)
        if (corners[std::size_t(k)] == u.value) spaced = rest[f.index()][std::size_t(k)];
    }
    if (!(spaced > 0.0) || !std::isfinite(spaced)) spaced = now;
    m.spaced[i + 1] = m.spaced[i] + spaced;
    m.current[i + 1] = m.current[i] + now;
  }
  return m;
}

// The inner fractions (along chain a, of its measure) of one pair's common points: `segments`
// pieces, the held inner vertices of both chains as breakpoints (b's at 1 - its own fraction:
// it runs the other way), each stretch between breakpoints cut into pieces in proportion to
// its length. A chain edge of a frozen face is a stretch of its own: both its ends are
// breakpoints that are never merged with a neighbour. It is one piece unless it measures (at
// rest, when given) more than 4/3 of the spacing; then it is split evenly, and its frozen
// face with it (a split is exact at rest).
std::vector<double> common_fractions(const SurfaceMesh& mesh, const SuturePair& pair,
                                     const ChainMeasure (&measure)[2], int segments,
                                     const std::vector<bool>& held, const std::vector<bool>& frozen) {
  struct Break {
    double at;
    bool strong;  // the end of a frozen edge: kept whatever its neighbours
  };
  std::vector<Break> breaks{{0.0, true}, {1.0, true}};
  for (const bool on_b : {false, true}) {
    const BoundaryChain& c = on_b ? pair.b : pair.a;
    const ChainMeasure& f = measure[on_b ? 1 : 0];
    const auto along_a = [&](double x) { return on_b ? 1.0 - x : x; };
    const std::size_t n = c.vertices.size();
    for (std::size_t i = 1; i < n; ++i)
      if (!held.empty() && held[c.vertices[i].index()] && (c.closed || i + 1 < n))
        breaks.push_back({along_a(f.fraction(i)), false});
    if (frozen.empty()) continue;
    for (std::size_t i = 0; i + (c.closed ? 0 : 1) < n; ++i) {
      const HalfedgeId h = detail::find_halfedge(mesh, c.vertices[i], c.vertices[(i + 1) % n]);
      if (!h.valid() || !frozen[SurfaceMesh::face(h).index()]) continue;
      const double u = along_a(f.fraction(i)), w = along_a(f.fraction(i + 1));
      breaks.push_back({u, true});
      breaks.push_back({w, true});
    }
  }
  std::sort(breaks.begin(), breaks.end(), [](const Break& x, const Break& y) {
    return x.at < y.at || (x.at == y.at && x.strong > y.strong);
  });
  // Breakpoints closer than a third of a piece are one (the join pairs them within 0.4); a
  // strong one displaces a weak one.
  const double close = 1.0 / (3.0 * segments);
  std::vector<Break> kept{breaks.front()};
  for (std::size_t i = 1; i < breaks.size(); ++i) {
    const Break& b = breaks[i];
    if (b.at - kept.back().at > close || (b.strong && b.at > kept.back().at)) {
      if (b.strong && b.at - kept.back().at <= close && !kept.back().strong) kept.back() = b;
      else kept.push_back(b);
    }
  }
  if (kept.back().at < 1.0) {
    if (1.0 - kept.back().at <= close && !kept.back().strong) kept.pop_back();
    kept.push_back({1.0, true});
  }
  std::vector<double> at;
  for (std::size_t i = 0; i + 1 < kept.size(); ++i) {
    const double span = kept[i + 1].at - kept[i].at;
    // As many pieces as the stretch holds, none longer than 4/3 of the spacing: the remesh
    // splits a longer edge (CGAL's isotropic split threshold), on one chain only.
    const double spacings = span * segments;
    const long pieces = std::max({1L, std::lround(spacings), static_cast<long>(std::ceil(0.75 * spacings - 1e-9))});
    if (i > 0) at.push_back(kept[i].at);
    for (long k = 1; k < pieces; ++k) at.push_back(kept[i].at + span * double(k) / double(pieces));
  }
  return at;
}

// The boundary's turn at boundary vertex v in the surface, degrees: |180 - the sum of its
// faces' angles at v| (0 on a straight run, about 180 at the tip of a slit). O(valence).
double boundary_turn_deg(const SurfaceMesh& mesh, VertexId v) {
  return std::abs(180.0 - vertex_angle_sum_deg(mesh, v));
}

}  // namespace

MatchedSeams match_seams(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs,
                         ResampleChainsParams params) {
  MatchedSeams m;
  // The vertices the remesh keeps: held ones and the ends of constrained polylines (an earlier
  // seam or a patch rim meeting the chain). Each must be a breakpoint of the common fractions;
  // one left between two new points would be an unmatched vertex, and the join would insert a
  // partner beside it (a needle triangle: 0.8 degrees after the widened anastomosis).
  std::vector<bool> held = params.constrained_vertices;
  held.resize(mesh.num_vertices(), false);
  for (const auto& [u, w] : params.constrained_edges) {
    if (!u.valid() || !w.valid() || u.index() >= held.size() || w.index() >= held.size()) continue;
    HalfedgeId h = detail::find_halfedge(mesh, u, w);
    if (!h.valid()) h = detail::find_halfedge(mesh, w, u);
    if (h.valid() && mesh.is_boundary(h)) continue;  // along a chain: its inner vertices may go
    held[u.index()] = held[w.index()] = true;
  }
  if (!(params.corner_turn_deg >= 0.0))
    throw InvalidArgument("match_seams: corner_turn_deg must be a number of degrees >= 0");
  // Sharp corners of a chain (the tip of a slit) are breakpoints too: collapsing the tip into
  // a lip neighbour shortens the incision, and where the fold test refuses that collapse the
  // tip stays between two common points, unmatched, and the join refuses the pair.
  for (const SuturePair& p : pairs)
    for (const BoundaryChain* c : {&p.a, &p.b})
      for (std::size_t i = c->closed ? 0 : 1; i + (c->closed ? 0 : 1) < c->vertices.size(); ++i)
        if (boundary_turn_deg(mesh, c->vertices[i]) > params.corner_turn_deg)
          held[c->vertices[i].index()] = true;
  std::vector<ChainResample> chains;
  double finest = HUGE_VAL;
  // Sizes first: the common points read both per face (found out of bounds by ASan).
  if (!params.frozen_faces.empty() && params.frozen_faces.size() != mesh.num_faces())
    throw InvalidArgument("match_seams: frozen_faces needs one entry per face");
  if (!params.rest_edge_lengths.empty() &&
      (params.rest_edge_lengths.size() != mesh.num_faces() || params.frozen_faces.size() != mesh.num_faces()))
    throw InvalidArgument("match_seams: rest_edge_lengths needs one entry per face, and frozen_faces");
  for (const SuturePair& p : pairs) {
    const double h = seam_spacing(mesh, p);
    const ChainMeasure measure[2] = {chain_measure(mesh, p.a, params.frozen_faces, params.rest_edge_lengths),
                                     chain_measure(mesh, p.b, params.frozen_faces, params.rest_edge_lengths)};
    const int segments = seam_segments(p, measure[0].length(), measure[1].length(), h);
    const std::vector<double> at = common_fractions(mesh, p, measure, segments, held, params.frozen_faces);
    // The same points along each chain in current length (b runs the other way).
    std::vector<double> at_a, at_b;
    for (const double x : at) at_a.push_back(measure[0].to_current(x));
    for (auto it = at.rbegin(); it != at.rend(); ++it) at_b.push_back(measure[1].to_current(1.0 - *it));
    m.spacing.push_back(h);
    finest = std::min(finest, h);
    chains.push_back({p.a, at_a});
    chains.push_back({p.b, at_b});
  }
  params.target_edge_length = finest;
  m.edit = resample_chains(mesh, chains, params);
  for (std::size_t i = 0; i < pairs.size(); ++i) m.pairs.push_back({m.edit.chains[2 * i], m.edit.chains[2 * i + 1]});
  return m;
}

}  // namespace sutura::engine
