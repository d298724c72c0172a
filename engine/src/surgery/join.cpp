#include "sutura/engine/surgery/join.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>

#include "mesh_walk.hpp"
#include "sutura/engine/errors.hpp"
#include "triangle_soup.hpp"

namespace sutura::engine {

namespace {

std::string point_text(const Vec3& x) {
  std::ostringstream os;
  os << "(" << x.x() << ", " << x.y() << ", " << x.z() << ")";
  return os.str();
}

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

// Monotone injective matching of the interior vertices of the coarse list (1..nc-2) to the
// interior vertices of the fine list (1..nf-2) minimising the summed parameter distance
// (dynamic programming, O(nc nf)). Returns, per coarse vertex, its fine partner.
std::vector<std::size_t> match_params(const std::vector<double>& sc, const std::vector<double>& sf) {
  const std::size_t nc = sc.size(), nf = sf.size();
  std::vector<std::size_t> partner(nc);
  partner[0] = 0;
  partner[nc - 1] = nf - 1;
  const std::size_t ic = nc - 2, jf = nf - 2;  // interior counts, ic <= jf
  if (ic == 0) return partner;
  const double inf = std::numeric_limits<double>::infinity();
  // cost[i][j]: best cost matching coarse interior 1..i to fine interior within 1..j.
  std::vector<std::vector<double>> cost(ic + 1, std::vector<double>(jf + 1, inf));
  for (std::size_t j = 0; j <= jf; ++j) cost[0][j] = 0.0;
  for (std::size_t i = 1; i <= ic; ++i)
    for (std::size_t j = i; j <= jf; ++j)
      cost[i][j] = std::min(cost[i][j - 1], cost[i - 1][j - 1] + std::abs(sc[i] - sf[j]));
  for (std::size_t i = ic, j = jf; i > 0; --j) {
    if (j > i && cost[i][j] == cost[i][j - 1]) continue;
    partner[i] = j;
    --i;
  }
  return partner;
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
                                   "between " + point_text(mesh.position(u)) + " and " +
                            point_text(mesh.position(v)));
  }
}

}  // namespace

JoinResult join(const SurfaceMesh& mesh, const std::vector<SuturePair>& pairs) {
  if (pairs.empty()) throw InvalidArgument("a join needs at least one pair of chains");
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

  detail::TriangleSoup soup(mesh);
  JoinResult result;
  std::vector<std::vector<std::pair<int, int>>> pair_vertices(pairs.size());
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const auto& [a, b] = pairs[p];
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
    SutureReport rep;
    rep.vertices_a = a.vertices.size();
    rep.vertices_b = b.vertices.size();
    rep.length_a = chain_length(mesh, a);
    rep.length_b = chain_length(mesh, b);
    const std::vector<double> sa = arc_params(mesh, A), sb = arc_params(mesh, B);
    std::vector<int> As(A.size()), Bs(B.size());
    for (std::size_t i = 0; i < A.size(); ++i) As[i] = A[i].value;
    for (std::size_t i = 0; i < B.size(); ++i) Bs[i] = B[i].value;
    if (A.size() != B.size()) {
      // Refine the coarser list: every fine vertex without a partner gets a new vertex on the
      // coarse edge between the partners of its matched neighbours, at the same relative arc
      // length, so the pairing stays monotone.
      const bool a_coarse = A.size() < B.size();
      std::vector<int>& C = a_coarse ? As : Bs;
      const std::vector<double>& sc = a_coarse ? sa : sb;
      const std::vector<double>& sf = a_coarse ? sb : sa;
      const std::vector<std::size_t> partner = match_params(sc, sf);
      std::vector<int> refined;
      for (std::size_t k = 0; k + 1 < C.size(); ++k) {
        refined.push_back(C[k]);
        const std::size_t j0 = partner[k], j1 = partner[k + 1];
        int u = C[k];
        double t_done = 0.0;
        for (std::size_t j = j0 + 1; j < j1; ++j) {
          const double t = (sf[j] - sf[j0]) / (sf[j1] - sf[j0]);
          u = soup.split_edge(u, C[k + 1], (t - t_done) / (1.0 - t_done));
          t_done = t;
          refined.push_back(u);
        }
      }
      refined.push_back(C.back());
      (a_coarse ? rep.inserted_a : rep.inserted_b) = int(refined.size() - C.size());
      C = std::move(refined);
    }
    for (std::size_t i = 0; i < As.size(); ++i) {
      pair_vertices[p].emplace_back(As[i], Bs[i]);
      rep.max_gap = std::max(rep.max_gap, (soup.position(As[i]) - soup.position(Bs[i])).norm());
    }
    result.sutures.push_back(rep);
  }

  // Merge partners (union-find: n >= 3 copies when sutures share vertices).
  UnionFind uf(soup.num_vertices());
  for (const auto& pv : pair_vertices)
    for (const auto& [x, y] : pv) uf.unite(x, y);
  std::vector<int> new_id(soup.num_vertices(), -1);
  std::vector<std::vector<int>> members;
  for (std::size_t v = 0; v < soup.num_vertices(); ++v) {
    const int r = uf.find(int(v));
    if (new_id[r] < 0) {
      new_id[r] = int(members.size());
      members.emplace_back();
    }
    new_id[v] = new_id[r];
    members[new_id[v]].push_back(int(v));
  }
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
      x += soup.position(v);
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
  }
  std::vector<FaceIndices> faces(soup.num_faces());
  maps.faces = sm.faces;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) faces[f][k] = new_id[soup.face(f)[k]];
    if (faces[f][0] == faces[f][1] || faces[f][1] == faces[f][2] || faces[f][0] == faces[f][2])
      throw InvalidArgument("the suture would collapse the triangle at " +
                            point_text(soup.position(soup.face(f)[0])) +
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
  for (const auto& pv : pair_vertices) {
    std::vector<VertexId> seam;
    for (const auto& [x, y] : pv) seam.emplace_back(new_id[x]);
    result.seams.push_back(std::move(seam));
  }
  return result;
}

}  // namespace sutura::engine
