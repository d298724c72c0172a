#include "suture_preview.hpp"

#include <cstdio>

#include "sutura/engine/surgery/boundary_chain.hpp"

namespace sutura::ui {

SuturePreview preview_suture(const engine::SurfaceMesh& mesh, const std::vector<engine::Vec3>& clicks) {
  SuturePreview p;
  std::vector<std::size_t> counts;
  for (std::size_t side = 0; side < 2 && 2 * side + 1 < clicks.size(); ++side) {
    engine::ChainSpec spec;
    spec.from = clicks[2 * side];
    spec.to = clicks[2 * side + 1];
    spec.max_distance = 3.0 * mesh.mean_edge_length();
    const char* name = side == 0 ? "A" : "B";
    try {
      const engine::BoundaryChain chain = engine::find_boundary_chain(mesh, spec);
      std::vector<engine::Vec3> pts;
      for (auto v : chain.vertices) pts.push_back(mesh.position(v));
      p.chains.push_back(std::move(pts));
      counts.push_back(chain.vertices.size());
      char buf[160];
      std::snprintf(buf, sizeof buf, "Side %s: %zu vertices, %.1f mm.", name,
                    chain.vertices.size(), engine::chain_length(mesh, chain));
      p.lines.emplace_back(buf);
    } catch (const std::exception& e) {
      p.lines.push_back(std::string("Side ") + name + ": " + e.what());
    }
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
