#include "suture_preview.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <utility>

#include "sutura/engine/surgery/boundary_chain.hpp"

namespace sutura::ui {

namespace {

// Suture clicks are boundary vertices' positions (the picker snaps them); the limit only
// explains a click that is not.
engine::ChainSpec spec(const engine::SurfaceMesh& mesh, const engine::Vec3& from, const engine::Vec3& to) {
  engine::ChainSpec s;
  s.from = from;
  s.to = to;
  s.loop = from == to;  // the same vertex clicked twice: its whole loop
  s.max_distance = 3.0 * mesh.mean_edge_length();
  return s;
}

std::optional<engine::BoundaryChain> resolve(const engine::SurfaceMesh& mesh, const engine::Vec3& from,
                                             const engine::Vec3& to) {
  try {
    return engine::find_boundary_chain(mesh, spec(mesh, from, to));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

using Edge = std::pair<int, int>;
std::set<Edge> edges_of(const engine::BoundaryChain& c) {
  std::set<Edge> e;
  for (std::size_t i = 0; i + 1 < c.vertices.size(); ++i)
    e.insert(std::minmax(c.vertices[i].value, c.vertices[i + 1].value));
  return e;
}

bool shares_an_edge(const engine::BoundaryChain& c, const std::set<Edge>& other) {
  for (std::size_t i = 0; i + 1 < c.vertices.size(); ++i)
    if (other.count(std::minmax(c.vertices[i].value, c.vertices[i + 1].value))) return true;
  return false;
}

}  // namespace

std::vector<engine::Vec3> orient_suture_clicks(const engine::SurfaceMesh& mesh,
                                               const std::vector<engine::Vec3>& clicks,
                                               std::array<bool, 2> long_way) {
  std::vector<engine::Vec3> out = clicks;
  std::set<Edge> side_a;
  for (std::size_t side = 0; side < 2 && 2 * side + 1 < out.size(); ++side) {
    const engine::Vec3 p = out[2 * side], q = out[2 * side + 1];
    if (p == q) continue;  // a whole loop: nothing to orient
    std::optional<engine::BoundaryChain> as_clicked = resolve(mesh, p, q), reversed = resolve(mesh, q, p);
    if (side == 1) {
      if (as_clicked && shares_an_edge(*as_clicked, side_a)) as_clicked.reset();
      if (reversed && shares_an_edge(*reversed, side_a)) reversed.reset();
    }
    bool swap = false;
    if (as_clicked && reversed) {
      const double a = engine::chain_length(mesh, *as_clicked), b = engine::chain_length(mesh, *reversed);
      const double tie = 1e-9 * std::max(a, b);  // equal arcs (two lips): keep the click order
      swap = long_way[side] ? b > a + tie : b < a - tie;
    } else {
      swap = !as_clicked && reversed;
    }
    if (swap) std::swap(out[2 * side], out[2 * side + 1]);
    if (side == 0) {
      if (auto chosen = swap ? reversed : as_clicked) side_a = edges_of(*chosen);
    }
  }
  return out;
}

SuturePreview preview_suture(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks,
                             std::array<bool, 2> long_way) {
  const std::vector<engine::Vec3> oriented = orient_suture_clicks(mesh, clicks, long_way);
  SuturePreview p;
  std::vector<std::size_t> counts;
  for (std::size_t side = 0; side < 2 && 2 * side + 1 < oriented.size(); ++side) {
    const char* name = side == 0 ? "A" : "B";
    try {
      const engine::BoundaryChain chain =
          engine::find_boundary_chain(mesh, spec(mesh, oriented[2 * side], oriented[2 * side + 1]));
      std::vector<engine::Vec3> pts;
      for (auto v : chain.vertices) pts.push_back(mesh.position(v));
      p.chains.push_back(std::move(pts));
      p.lengths.push_back(engine::chain_length(mesh, chain));
      counts.push_back(chain.vertices.size());
      char buf[160];
      std::snprintf(buf, sizeof buf, "Side %s: %zu vertices, %.1f mm%s.", name, chain.vertices.size(),
                    p.lengths.back(),
                    chain.closed ? ", a whole loop" : long_way[side] ? ", the long way round" : "");
      p.lines.emplace_back(buf);
    } catch (const std::exception& e) {
      p.lines.push_back(std::string("Side ") + name + ": " + e.what());
    }
  }
  const auto loop_side = [&](std::size_t side) { return oriented[2 * side] == oriented[2 * side + 1]; };
  if (p.chains.size() == 2 && loop_side(0) && loop_side(1)) {
    p.meeting_ends.push_back({p.chains[0].front(), p.chains[1].front()});
    p.lines.emplace_back("Two whole loops (an end-to-end anastomosis): they meet at the grey line, "
                         "where you clicked, and run round in opposite directions.");
  } else if (p.chains.size() == 2) {
    p.meeting_ends.push_back({p.chains[0].front(), p.chains[1].back()});
    p.meeting_ends.push_back({p.chains[0].back(), p.chains[1].front()});
    p.lines.emplace_back("The grey lines show which ends meet.");
  }
  if (counts.size() == 2 && counts[0] != counts[1]) {
    const std::size_t diff = counts[0] > counts[1] ? counts[0] - counts[1] : counts[1] - counts[0];
    p.lines.push_back("The sides differ by " + std::to_string(diff) +
                      " vertices: the join pairs them by arc length and splits edges of side " +
                      (counts[0] < counts[1] ? "A" : "B") + " to add the missing " +
                      std::to_string(diff) + ", so the seam is still one to one.");
  } else if (counts.size() == 2) {
    p.lines.emplace_back("Equal counts: every vertex of A meets one of B.");
  }
  return p;
}

}  // namespace sutura::ui
