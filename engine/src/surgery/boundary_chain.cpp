#include "sutura/engine/surgery/boundary_chain.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

#include "mesh_walk.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// Loop index and position within it for every boundary vertex.
struct LoopIndex {
  std::vector<std::vector<VertexId>> loops;
  std::vector<std::pair<int, int>> where;  // per vertex; (-1, -1) = interior
  explicit LoopIndex(const SurfaceMesh& mesh)
      : loops(mesh.boundary_loops()), where(mesh.num_vertices(), {-1, -1}) {
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (std::size_t i = 0; i < loops[l].size(); ++i)
        where[loops[l][i].index()] = {int(l), int(i)};
  }
};

BoundaryChain arc(const LoopIndex& index, VertexId from, VertexId to) {
  const auto [lf, i_from] = index.where[from.index()];
  const auto& loop = index.loops[lf];
  BoundaryChain c;
  c.closed = from == to;
  const std::size_t n = loop.size();
  for (std::size_t k = 0; k < n; ++k) {
    const VertexId v = loop[(i_from + k) % n];
    if (k > 0 && v == to) {
      c.vertices.push_back(v);
      break;
    }
    c.vertices.push_back(v);
  }
  return c;
}

}  // namespace

BoundaryChain boundary_chain(const SurfaceMesh& mesh, VertexId from, VertexId to) {
  const LoopIndex index(mesh);
  for (const VertexId v : {from, to})
    if (!v.valid() || v.index() >= mesh.num_vertices() || index.where[v.index()].first < 0)
      throw InvalidArgument("vertex " + std::to_string(v.value) + " is not on the boundary");
  if (index.where[from.index()].first != index.where[to.index()].first)
    throw InvalidArgument("vertices " + std::to_string(from.value) + " and " +
                          std::to_string(to.value) + " lie on different boundary loops");
  return arc(index, from, to);
}

double chain_length(const SurfaceMesh& mesh, const BoundaryChain& chain) {
  double len = 0.0;
  const auto& v = chain.vertices;
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    len += (mesh.position(v[i + 1]) - mesh.position(v[i])).norm();
  if (chain.closed && v.size() > 1) len += (mesh.position(v.front()) - mesh.position(v.back())).norm();
  return len;
}

BoundaryChain find_boundary_chain(const SurfaceMesh& mesh, const ChainSpec& spec) {
  const LoopIndex index(mesh);
  if (index.loops.empty()) throw InvalidArgument("the object has no open boundary to suture");
  // Boundary vertices nearest a point; coincident copies (the two lips of a fresh cut) are
  // all returned so that the arc choice below can pick between them.
  auto nearest = [&](const Vec3& p, const char* what) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& loop : index.loops)
      for (const VertexId v : loop) best = std::min(best, (mesh.position(v) - p).norm());
    if (best > spec.max_distance)
      throw InvalidArgument(std::string("chain point '") + what + "' " + detail::point_text(p) +
                            " is " + std::to_string(best) +
                            " mm from the nearest boundary vertex (limit " +
                            std::to_string(spec.max_distance) + " mm)");
    const double tol = best + 1e-9 * (1.0 + best) + 1e-12 * mesh.bounds().diagonal().norm();
    std::vector<VertexId> out;
    for (const auto& loop : index.loops)
      for (const VertexId v : loop)
        if ((mesh.position(v) - p).norm() <= tol) out.push_back(v);
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto from = nearest(spec.from, "from");
  if (spec.loop) {
    BoundaryChain c = arc(index, from.front(), from.front());
    c.closed = true;
    return c;
  }
  const auto to = nearest(spec.to, "to");
  BoundaryChain best;
  double best_key = std::numeric_limits<double>::infinity();
  bool different_loops = false;
  for (const VertexId f : from)
    for (const VertexId t : to) {
      if (f == t) continue;
      if (index.where[f.index()].first != index.where[t.index()].first) {
        different_loops = true;
        continue;
      }
      BoundaryChain c = arc(index, f, t);
      double key = chain_length(mesh, c);
      if (spec.via) {
        double d = std::numeric_limits<double>::infinity();
        for (const VertexId v : c.vertices) d = std::min(d, (mesh.position(v) - *spec.via).norm());
        key = d;  // nearest arc to the via point; ties keep the first (lowest ids)
      }
      if (key < best_key) {
        best_key = key;
        best = std::move(c);
      }
    }
  if (best.vertices.empty()) {
    if (different_loops)
      throw InvalidArgument("chain points 'from' " + detail::point_text(spec.from) + " and 'to' " +
                            detail::point_text(spec.to) + " lie on different boundary loops");
    throw InvalidArgument("chain points 'from' and 'to' pick the same boundary vertex at " +
                          detail::point_text(mesh.position(from.front())) +
                          "; use a loop chain for a whole boundary loop");
  }
  return best;
}

}  // namespace sutura::engine
