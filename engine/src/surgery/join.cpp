#include "sutura/engine/surgery/join.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "shape_deformation.hpp"
#include "mesh_walk.hpp"
#include "sutura/engine/errors.hpp"
#include "triangle_soup.hpp"

namespace sutura::engine {

namespace {

std::string suture_name(std::size_t i) { return "suture " + std::to_string(i + 1); }

// Normalised arc-length parameter of every vertex of an open vertex list.
std::vector<double> arc_params(const SurfaceMesh& mesh, const std::vector<VertexId>& v) {
  std::vector<double> s(v.size(), 0.0);
  for (std::size_t i = 1; i < v.size(); ++i)
    s[i] = s[i - 1] + (mesh.position(v[i]) - mesh.position(v[i - 1])).norm();
  const double total = s.back();
  if (total > 0)
    for (double& x : s) x /= total;
  return s;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

void check_chain(const SurfaceMesh& mesh, const BoundaryChain& c, const std::string& name) {
  const std::size_t n = c.vertices.size();
  if (n < (c.closed ? 3u : 2u))
    throw InvalidArgument(name + " has " + std::to_string(n) + " vertices; a suture needs at least " +
                          (c.closed ? "3 (closed loop)" : "2"));
  std::set<VertexId> seen;
  for (const VertexId v : c.vertices) {
    if (!v.valid() || v.index() >= mesh.num_vertices())
      throw InvalidArgument(name + " references vertex " + std::to_string(v.value) +
                            " which does not exist");
    if (!seen.insert(v).second)
      throw InvalidArgument(name + " visits vertex " + std::to_string(v.value) + " twice");
  }
  for (std::size_t i = 0; i + (c.closed ? 0 : 1) < n; ++i) {
    const VertexId u = c.vertices[i], v = c.vertices[(i + 1) % n];
    const HalfedgeId h = detail::find_halfedge(mesh, u, v);
    if (!h.valid() || !mesh.is_boundary(h))
      throw InvalidArgument(name + " is not a run of boundary edges in the boundary direction "
                                   "between " + detail::point_text(mesh.position(u)) + " and " +
                            detail::point_text(mesh.position(v)));
  }
}

// Phase 1: each chain is a run of boundary edges in the boundary direction, no edge is
// sutured twice, and loops pair with loops.
void check_pairs(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs,
                 const JoinParams& params) {
  if (!params.held.empty() && params.held.size() != mesh.num_vertices())
    throw InvalidArgument("join: " + std::to_string(params.held.size()) + " held flags for " +
                          std::to_string(mesh.num_vertices()) + " vertices");
  if (pairs.empty()) throw InvalidArgument("a join needs at least one pair of chains");
  if (params.rigid_iterations < 0 || params.rigid_stages < 1)
    throw InvalidArgument("join: rigid_iterations must be >= 0 and rigid_stages >= 1");
  // Validate chains and reject overlaps (a chain sutured to itself or used twice).
  std::map<std::pair<int, int>, std::string> used_edges;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto& [a, b] = pairs[p];
    check_chain(mesh, a, suture_name(p) + ", chain 1");
    check_chain(mesh, b, suture_name(p) + ", chain 2");
    if (a.closed != b.closed)
      throw InvalidArgument(suture_name(p) + ": chain " + (a.closed ? "1" : "2") +
                            " is a closed loop but chain " + (a.closed ? "2" : "1") +
                            " is not; a loop can only be sutured to a loop");
    for (int which = 0; which < 2; ++which) {
      const BoundaryChain& c = which == 0 ? a : b;
      const std::string name = suture_name(p) + ", chain " + std::to_string(which + 1);
      const std::size_t n = c.vertices.size();
      for (std::size_t i = 0; i + (c.closed ? 0 : 1) < n; ++i) {
        const auto key = std::make_pair(c.vertices[i].value, c.vertices[(i + 1) % n].value);
        const auto [it, fresh] = used_edges.emplace(key, name);
        if (!fresh)
          throw InvalidArgument(name + " overlaps " + it->second + " (a chain cannot be sutured "
                                "to itself or used twice)");
      }
    }
  }
}

// Phase 2, on the soup before any pairing. Where both chains end at one shared vertex e (a slit
// end, or the corner where a flap meets its bed), the suture closes e's fan like a cone: the
// faces of e between its two chain edges close up around it, which needs at least three of them
// (with two, merging the neighbours would stack both faces onto one edge). Too small a fan gets
// a vertex on the outer edge of its face with the widest angle at e, where that angle's
// bisector meets it, which adds one face at e each time and halves that angle: the cone's faces
// stay as wide as they can (docs/remeshing.md, the subclavian flap).
void widen_fan(detail::TriangleSoup& soup, int e) {
  for (int guard = 0; guard < 4; ++guard) {
    int count = 0, widest = -1;
    double widest_angle = -1.0;
    for (std::size_t f = 0; f < soup.num_faces(); ++f) {
      const FaceIndices& t = soup.face(f);
      for (int k = 0; k < 3; ++k)
        if (t[k] == e) {
          ++count;
          const Vec3 u = soup.position(t[(k + 1) % 3]) - soup.position(e);
          const Vec3 w = soup.position(t[(k + 2) % 3]) - soup.position(e);
          const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
          if (angle > widest_angle) widest_angle = angle, widest = int(f);
        }
    }
    if (count >= 3 || widest < 0) return;
    const FaceIndices& t = soup.face(widest);
    int k = 0;
    while (t[k] != e) ++k;
    const int u = t[(k + 1) % 3], w = t[(k + 2) % 3];
    const double lu = (soup.position(u) - soup.position(e)).norm();
    const double lw = (soup.position(w) - soup.position(e)).norm();
    // The bisector divides uw as eu : ew (a zero-area face: at its midpoint).
    soup.split_edge(u, w, lu + lw > 0.0 ? lu / (lu + lw) : 0.5);
  }
}

void widen_zipper_fans(detail::TriangleSoup& soup, const std::vector<SuturePair>& pairs) {
  for (const auto& [a, b] : pairs) {
    if (a.closed) continue;
    if (a.vertices.front() == b.vertices.back()) widen_fan(soup, a.vertices.front().value);
    if (a.vertices.back() == b.vertices.front()) widen_fan(soup, a.vertices.back().value);
  }
}

struct PairedSuture {
  std::vector<std::pair<int, int>> partners;  ///< soup vertices (a copy, b copy), in order
  SutureReport report;
};

// Phase 3: the partners of one suture, by arc length; inserts partners into the soup.
PairedSuture pair_by_arc_length(const SurfaceMesh& mesh, detail::TriangleSoup& soup,
                                const SuturePair& pair, std::size_t p,
                                const JoinParams& params) {
  PairedSuture out;
  const auto& [a, b] = pair;
  // A runs along a; B runs along b backwards, so A[i] and B[i] are partners. A closed loop
  // is opened at its first vertex, which both ends of the list repeat.
  std::vector<VertexId> A = a.vertices, B(b.vertices.rbegin(), b.vertices.rend());
  if (a.closed) {
    A.push_back(A.front());
    // B = b0, b_{n-1}, ..., b1, b0
    B.assign(1, b.vertices.front());
    for (std::size_t i = b.vertices.size() - 1; i >= 1; --i) B.push_back(b.vertices[i]);
    B.push_back(b.vertices.front());
  }
  SutureReport& rep = out.report;
  rep.vertices_a = a.vertices.size();
  rep.vertices_b = b.vertices.size();
  rep.length_a = chain_length(mesh, a);
  rep.length_b = chain_length(mesh, b);
  const std::vector<double> sa = arc_params(mesh, A), sb = arc_params(mesh, B);
  std::vector<int> As(A.size()), Bs(B.size());
  for (std::size_t i = 0; i < A.size(); ++i) As[i] = A[i].value;
  for (std::size_t i = 0; i < B.size(); ++i) Bs[i] = B[i].value;
  // Pair by arc length. Vertices of the two chains at (nearly) the same normalised arc
  // length are partners; every other vertex gets a partner inserted on the other chain's
  // edge at its arc length. Pairing existing vertices that lie apart would suture rest
  // points that do not correspond and leave a shear defect along the seam; a partner is
  // accepted within kMatch of the local spacing (the sliver guard of the insertion). 0.4 by
  // measurement: at 0.2 two loops of 32 and 34 vertices got seam triangles a tenth of the
  // spacing wide that stalled the relaxation of an anastomosis; at 0.5 the two strips of
  // 4 and 6 edges pair vertices 1/12 of the width apart and the seam no longer stays
  // symmetric (the closed-form check of the Fig. 2.4 session fails).
  constexpr double kMatch = 0.4;
  auto spacing = [](const std::vector<double>& t, std::size_t i) {
    return std::min(t[i] - t[i - 1], t[i + 1] - t[i]);
  };
  if (params.pairing == JoinPairing::InOrder && As.size() != Bs.size())
    throw InvalidArgument(suture_name(p) + ": chains of " + std::to_string(a.vertices.size()) +
                          " and " + std::to_string(b.vertices.size()) +
                          " vertices cannot be paired in order");
  std::vector<int> RA{As.front()}, RB{Bs.front()};
  double ta_last = 0.0, tb_last = 0.0;
  std::size_t i = 1, j = 1;
  const std::size_t na = As.size(), nb = Bs.size();
  if (params.pairing == JoinPairing::InOrder) {  // partners as given: nothing to insert
    RA.assign(As.begin(), As.end() - 1);
    RB.assign(Bs.begin(), Bs.end() - 1);
    i = na - 1;
    j = nb - 1;
  }
  while (i + 1 < na || j + 1 < nb) {
    const double ta = i + 1 < na ? sa[i] : 2.0, tb = j + 1 < nb ? sb[j] : 2.0;
    const double tol = kMatch * std::min(i + 1 < na ? spacing(sa, i) : 1.0,
                                         j + 1 < nb ? spacing(sb, j) : 1.0);
    if (std::abs(ta - tb) <= tol) {
      RA.push_back(As[i++]);
      RB.push_back(Bs[j++]);
      ta_last = ta, tb_last = tb;
    } else if (ta < tb) {
      // Partner for A[i] on B's edge (last B vertex, B[j]).
      const double t = (ta - tb_last) / (sb[j] - tb_last);
      RB.push_back(soup.split_edge(RB.back(), Bs[j], t));
      RA.push_back(As[i++]);
      ++rep.inserted_b;
      ta_last = tb_last = ta;
    } else {
      const double t = (tb - ta_last) / (sa[i] - ta_last);
      RA.push_back(soup.split_edge(RA.back(), As[i], t));
      RB.push_back(Bs[j++]);
      ++rep.inserted_a;
      ta_last = tb_last = tb;
    }
  }
  RA.push_back(As.back());
  RB.push_back(Bs.back());
  As = std::move(RA);
  Bs = std::move(RB);
  for (std::size_t i = 0; i < As.size(); ++i) {
    out.partners.emplace_back(As[i], Bs[i]);
    rep.max_gap = std::max(rep.max_gap, (soup.position(As[i]) - soup.position(Bs[i])).norm());
  }
  return out;
}

// The soup's vertices grouped into the joined mesh's vertices.
struct Groups {
  std::vector<int> new_id;                ///< soup vertex -> joined vertex
  std::vector<std::vector<int>> members;  ///< joined vertex -> its soup copies, ascending
};

// Phase 4: partners merge (union-find: n >= 3 copies when sutures share vertices).
Groups merge_partners(std::size_t num_vertices, const std::vector<PairedSuture>& sutures) {
  UnionFind uf(num_vertices);
  for (const PairedSuture& s : sutures)
    for (const auto& [x, y] : s.partners) uf.unite(x, y);
  Groups g;
  std::vector<int>& new_id = g.new_id;
  std::vector<std::vector<int>>& members = g.members;
  new_id.assign(num_vertices, -1);
  for (std::size_t v = 0; v < num_vertices; ++v) {
    const int r = uf.find(int(v));
    if (new_id[r] < 0) {
      new_id[r] = int(members.size());
      members.emplace_back();
    }
    new_id[v] = new_id[r];
    members[new_id[v]].push_back(int(v));
  }
  return g;
}

struct Placement {
  std::vector<Vec3> moved;      ///< per soup vertex, before copies meet at their mean
  std::vector<bool> displaced;  ///< moved by the placement
};

// Phase 5, where each copy goes: OntoB moves every copy to its group's b copies and carries the
// rest of the mesh along as rigidly as possible (free vertices follow, held ones stay);
// Mean moves nothing but the copies, which meet at their mean below.
Placement place_copies(const detail::TriangleSoup& soup, const Groups& groups,
                       const std::vector<PairedSuture>& sutures, const JoinParams& params) {
  Placement out;
  std::vector<Vec3>& moved = out.moved;
  moved.resize(soup.num_vertices());
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) moved[v] = soup.position(int(v));
  std::vector<bool>& displaced = out.displaced;
  displaced.assign(soup.num_vertices(), false);
  if (params.placement == SuturePlacement::OntoB) {
    std::vector<bool> on_b(soup.num_vertices(), false);
    for (const PairedSuture& s : sutures)
      for (const auto& [x, y] : s.partners) on_b[y] = true;
    std::vector<bool> prescribed(soup.num_vertices(), false);
    std::vector<Vec3> value(soup.num_vertices(), Vec3::Zero());
    for (std::size_t v = 0; v < params.held.size(); ++v) prescribed[v] = params.held[v];
    for (const auto& mem : groups.members) {
      if (mem.size() < 2) continue;
      Vec3 target = Vec3::Zero();
      int count = 0;
      for (const int v : mem)
        if (on_b[v]) target += soup.position(v), ++count;
      target /= double(count);  // every group holds a b copy: it was made by pairing a with b
      for (const int v : mem) {
        prescribed[v] = true;
        value[v] = target - soup.position(v);
      }
    }
    std::vector<FaceIndices> soup_faces(soup.num_faces());
    for (std::size_t f = 0; f < soup.num_faces(); ++f) soup_faces[f] = soup.face(int(f));
    const std::vector<Vec3> placed = detail::as_rigid_as_possible(
        moved, soup_faces, prescribed, value, params.rigid_iterations, params.rigid_stages);
    // Parts the suture does not pull on come back from the solve with round-off changes
    // only; they keep their positions bit for bit (and their rest shapes stay as they are).
    Eigen::AlignedBox3d box;
    for (const Vec3& x : moved) box.extend(x);
    const double negligible = 1e-12 * box.diagonal().norm();
    for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
      if ((placed[v] - moved[v]).norm() <= negligible) continue;
      displaced[v] = true;
      moved[v] = placed[v];
    }
  }
  return out;
}

// Phase 6: the joined mesh, its maps (each vertex its copies' parents' mean) and seams.
void assemble(const detail::TriangleSoup& soup, const Groups& groups, const Placement& placement,
              const std::vector<PairedSuture>& sutures, JoinResult& result) {
  const std::vector<int>& new_id = groups.new_id;
  const std::vector<std::vector<int>>& members = groups.members;
  const std::vector<Vec3>& moved = placement.moved;
  const std::vector<bool>& displaced = placement.displaced;
  const EditMaps& sm = soup.maps();
  std::vector<Vec3> positions(members.size());
  EditMaps maps;
  maps.vertices.resize(members.size());
  for (std::size_t g = 0; g < members.size(); ++g) {
    const auto& mem = members[g];
    Vec3 x = Vec3::Zero();
    std::map<std::int32_t, double> acc;
    VertexOrigin& o = maps.vertices[g];
    o.kind = mem.size() > 1 ? VertexOriginKind::Merged : sm.vertices[mem[0]].kind;
    for (const int v : mem) {
      x += moved[v];
      const VertexOrigin& so = sm.vertices[v];
      if (mem.size() == 1) o.kind = so.kind;
      for (std::size_t j = 0; j < so.parents.size(); ++j)
        acc[so.parents[j].value] += so.weights[j] / double(mem.size());
    }
    positions[g] = x / double(mem.size());
    for (const auto& [id, w] : acc) {
      o.parents.emplace_back(id);
      o.weights.push_back(w);
    }
    if (mem.size() > 1) result.merged.emplace_back(g);
    else if (displaced[mem[0]]) result.displaced.emplace_back(g);
  }
  std::vector<FaceIndices> faces(soup.num_faces());
  maps.faces = sm.faces;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) faces[f][k] = new_id[soup.face(f)[k]];
    if (faces[f][0] == faces[f][1] || faces[f][1] == faces[f][2] || faces[f][0] == faces[f][2])
      throw InvalidArgument("the suture would collapse the triangle at " +
                            detail::point_text(soup.position(soup.face(f)[0])) +
                            " (its corners are paired with each other); the chains are adjacent "
                            "there");
  }
  try {
    result.mesh = SurfaceMesh(std::move(positions), std::move(faces));
  } catch (const TopologyError& e) {
    throw InvalidArgument(std::string("the suture would make the surface invalid (") + e.what() +
                          "); check that both chains follow the boundary direction and that "
                          "they do not cross other sutures");
  }
  result.maps = std::move(maps);
  for (const PairedSuture& s : sutures) {
    std::vector<VertexId> seam;
    for (const auto& [x, y] : s.partners) seam.emplace_back(new_id[x]);
    result.seams.push_back(std::move(seam));
  }
}

}  // namespace

SuturePlacement parse_suture_placement(const std::string& name) {
  if (name == "mean") return SuturePlacement::Mean;
  if (name == "onto_b") return SuturePlacement::OntoB;
  throw InvalidArgument("unknown suture placement '" + name + "' (expected mean or onto_b)");
}

JoinResult join(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs,
                const JoinParams& params) {
  check_pairs(mesh, pairs, params);
  detail::TriangleSoup soup(mesh);
  widen_zipper_fans(soup, pairs);
  JoinResult result;
  std::vector<PairedSuture> sutures;
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    sutures.push_back(pair_by_arc_length(mesh, soup, pairs[p], p, params));
    result.sutures.push_back(sutures.back().report);
  }
  const Groups groups = merge_partners(soup.num_vertices(), sutures);
  const Placement placement = place_copies(soup, groups, sutures, params);
  assemble(soup, groups, placement, sutures, result);
  return result;
}

}  // namespace sutura::engine
