#include "sutura/app/suture_preview.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <utility>

#include "sutura/engine/surgery/boundary_chain.hpp"

namespace sutura::app {

namespace {

// Suture clicks are boundary vertices' positions (the picker snaps them); the limit only
// explains a click that is not.
engine::ChainSpec spec(const engine::SurfaceMesh& mesh, const ChainEnds& ends) {
  engine::ChainSpec s;
  s.from = ends.from;
  s.to = ends.to;
  s.via = ends.via;
  s.loop = ends.loop();
  s.max_distance = 3.0 * mesh.mean_edge_length();
  return s;
}

std::optional<engine::BoundaryChain> resolve(const engine::SurfaceMesh& mesh, const ChainEnds& ends) {
  try {
    return engine::find_boundary_chain(mesh, spec(mesh, ends));
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

struct Candidate {
  ChainEnds ends;
  engine::BoundaryChain chain;
};

// The arcs a side's two clicks can name, in the boundary direction.
std::vector<Candidate> candidates(const engine::SurfaceMesh& mesh, const engine::Vec3& p, const engine::Vec3& q,
                                  bool lip_to_lip) {
  std::vector<Candidate> out;
  if (p != q) {
    for (const ChainEnds& ends : {ChainEnds{p, q, {}}, ChainEnds{q, p, {}}})
      if (auto c = resolve(mesh, ends)) out.push_back({ends, std::move(*c)});
    return out;
  }
  // The ends at one point: its whole loop; or, lip to lip, where two lips have a copy each,
  // the two arcs between the copies (the resolution without `via` is the shorter one).
  engine::ChainSpec between = spec(mesh, ChainEnds{p, p, p});
  between.via.reset();
  std::optional<engine::BoundaryChain> shorter;
  if (lip_to_lip) {
    try {
      shorter = engine::find_boundary_chain(mesh, between);
    } catch (const std::exception&) {  // a single vertex there: its loop
    }
  }
  if (shorter) {
    const engine::BoundaryChain other =
        engine::boundary_chain(mesh, shorter->vertices.back(), shorter->vertices.front());
    out.push_back({ChainEnds{p, p, p}, std::move(*shorter)});
    out.push_back({ChainEnds{p, p, p}, other});
  } else if (auto loop = resolve(mesh, ChainEnds{p, p, {}})) {
    out.push_back({ChainEnds{p, p, {}}, std::move(*loop)});
  }
  return out;
}

// `ends` with `via` set, if needed, so that the join resolves exactly `chain`: none when the
// ends alone do; otherwise a vertex of the chain (from its middle outwards) that picks it, or
// failing that its middle vertex.
ChainEnds naming(const engine::SurfaceMesh& mesh, ChainEnds ends, const engine::BoundaryChain& chain) {
  if (ends.loop()) return ends;
  ends.via.reset();
  if (ends.from != ends.to) {
    const auto plain = resolve(mesh, ends);
    if (plain && plain->vertices == chain.vertices) return ends;
  }
  const std::size_t n = chain.vertices.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = k % 2 == 0 ? n / 2 + k / 2 : n / 2 - (k + 1) / 2;
    if (i >= n) continue;
    ends.via = mesh.position(chain.vertices[i]);
    const auto named = resolve(mesh, ends);
    if (named && named->vertices == chain.vertices) return ends;
  }
  // No vertex names it alone (coincident copies of several cuts tie): keep the middle one.
  // Never fall back to the ends alone, which at one point would be read as the whole loop;
  // the preview shows what the join resolves from this.
  ends.via = mesh.position(chain.vertices[n / 2]);
  return ends;
}

}  // namespace

std::vector<ChainEnds> suture_sides(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks,
                                    std::array<bool, 2> long_way, bool lip_to_lip) {
  std::vector<ChainEnds> out;
  std::set<Edge> side_a;
  for (std::size_t side = 0; side < 2 && 2 * side + 1 < clicks.size(); ++side) {
    const engine::Vec3 p = clicks[2 * side], q = clicks[2 * side + 1];
    std::vector<Candidate> c = candidates(mesh, p, q, lip_to_lip);
    if (side == 1)
      c.erase(std::remove_if(c.begin(), c.end(),
                             [&](const Candidate& k) { return shares_an_edge(k.chain, side_a); }),
              c.end());
    if (c.empty()) {
      out.push_back(ChainEnds{p, q, {}});
      continue;
    }
    std::size_t pick = 0;
    if (c.size() == 2) {
      const double a = engine::chain_length(mesh, c[0].chain), b = engine::chain_length(mesh, c[1].chain);
      const double tie = 1e-9 * std::max(a, b);  // equal arcs (two lips): keep the first
      pick = (long_way[side] ? b > a + tie : b < a - tie) ? 1 : 0;
    }
    out.push_back(naming(mesh, c[pick].ends, c[pick].chain));
    if (side == 0) side_a = edges_of(c[pick].chain);
  }
  return out;
}

SuturePreview preview_suture(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks,
                             std::array<bool, 2> long_way, bool lip_to_lip) {
  const std::vector<ChainEnds> sides = suture_sides(mesh, clicks, long_way, lip_to_lip);
  SuturePreview p;
  std::vector<std::size_t> counts;
  bool around_any = false;
  for (std::size_t side = 0; side < sides.size(); ++side) {
    const char* name = side == 0 ? "A" : "B";
    try {
      const engine::BoundaryChain chain = engine::find_boundary_chain(mesh, spec(mesh, sides[side]));
      std::vector<engine::Vec3> pts;
      for (auto v : chain.vertices) pts.push_back(mesh.position(v));
      p.chains.push_back(std::move(pts));
      p.lengths.push_back(engine::chain_length(mesh, chain));
      counts.push_back(chain.vertices.size());
      const bool around = sides[side].from == sides[side].to && sides[side].via;
      around_any = around_any || around;
      char buf[200];
      std::snprintf(buf, sizeof buf, "Side %s: %zu vertices, %.1f mm%s%s.", name, chain.vertices.size(),
                    p.lengths.back(),
                    chain.closed ? ", a whole loop" : around ? ", from one lip round to the other" : "",
                    !chain.closed && long_way[side] ? ", the long way round" : "");
      p.lines.emplace_back(buf);
    } catch (const std::exception& e) {
      p.lines.push_back(std::string("Side ") + name + ": " + e.what());
    }
  }
  const bool loops = sides.size() == 2 && sides[0].loop() && sides[1].loop();
  if (p.chains.size() == 2 && loops) {
    p.meeting_ends.push_back({p.chains[0].front(), p.chains[1].front()});
    p.lines.emplace_back("Two whole loops (an end-to-end anastomosis): they meet at the grey line, "
                         "where you clicked, and run round in opposite directions.");
  } else if (p.chains.size() == 2) {
    p.meeting_ends.push_back({p.chains[0].front(), p.chains[1].back()});
    p.meeting_ends.push_back({p.chains[0].back(), p.chains[1].front()});
    p.lines.emplace_back(around_any ? "Both sides start and end at the point you clicked, where "
                                      "the lips meet; tick 'long way round' to swap the arcs."
                                    : "The grey lines show which ends meet.");
  }
  if (p.lengths.size() == 2 && std::min(p.lengths[0], p.lengths[1]) > 0.0 &&
      std::max(p.lengths[0], p.lengths[1]) > 2.0 * std::min(p.lengths[0], p.lengths[1])) {
    const bool a_longer = p.lengths[0] > p.lengths[1];
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "Warning: side %s is %.1f times as long as side %s; the seam gathers it onto "
                  "the shorter side. Check the ends you clicked.",
                  a_longer ? "A" : "B", std::max(p.lengths[0], p.lengths[1]) / std::min(p.lengths[0], p.lengths[1]),
                  a_longer ? "B" : "A");
    p.lines.emplace_back(buf);
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

}  // namespace sutura::app
