#include "nodal_rotations.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "../geometry/best_rotation.hpp"
#include "../shell/parallel_loop.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

NodalRotations::NodalRotations(const std::vector<FaceIndices>& faces, std::size_t num_nodes)
    : offset_(num_nodes + 1, 0) {
  std::vector<std::vector<int>> ring(num_nodes);
  for (const FaceIndices& f : faces)
    for (int k = 0; k < 3; ++k) {
      const auto a = f[k], b = f[(k + 1) % 3];
      if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= num_nodes ||
          static_cast<std::size_t>(b) >= num_nodes)
        throw InvalidArgument("NodalRotations: a face references node " +
                              std::to_string(std::min(a, b) < 0 ? std::min(a, b) : std::max(a, b)) +
                              " of " + std::to_string(num_nodes));
      ring[a].push_back(b);
      ring[b].push_back(a);
    }
  for (std::size_t i = 0; i < num_nodes; ++i) {
    std::sort(ring[i].begin(), ring[i].end());
    ring[i].erase(std::unique(ring[i].begin(), ring[i].end()), ring[i].end());
    offset_[i + 1] = offset_[i] + static_cast<int>(ring[i].size());
  }
  neighbour_.reserve(offset_.back());
  for (const auto& r : ring) neighbour_.insert(neighbour_.end(), r.begin(), r.end());
}

double NodalRotations::compute(const std::vector<Vec3>& reference,
                               const std::vector<Vec3>& current,
                               std::vector<Eigen::Matrix3d>& out) const {
  const std::size_t n = offset_.size() - 1;
  if (reference.size() != n || current.size() != n)
    throw InvalidArgument("NodalRotations: " + std::to_string(n) + " positions needed, got " +
                          std::to_string(reference.size()) + " and " +
                          std::to_string(current.size()));
  // Warm start: Newton from the rotations passed in (refine_best_rotation), the SVD where
  // there are none or Newton does not converge.
  const bool warm = out.size() == n;
  out.resize(n);
  bend_.resize(n);
  for_each_index(n, [&](std::size_t i) {
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    for (int k = offset_[i]; k < offset_[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(neighbour_[k]);
      S += (reference[j] - reference[i]) * (current[j] - current[i]).transpose();
    }
    if (offset_[i] == offset_[i + 1]) {
      out[i].setIdentity();
    } else if (!(warm && refine_best_rotation(S, out[i]))) {
      out[i] = best_rotation(S);
    }
  });
  // How far the shell bent: the largest angle between the rotations of neighbouring nodes,
  // from the smallest cosine, cos = (tr(Q_i^T Q_j) - 1) / 2.
  for_each_index(n, [&](std::size_t i) {
    double lowest = 1.0;
    for (int k = offset_[i]; k < offset_[i + 1]; ++k) {
      const auto j = static_cast<std::size_t>(neighbour_[k]);
      lowest = std::min(lowest, 0.5 * (out[i].cwiseProduct(out[j]).sum() - 1.0));
    }
    bend_[i] = lowest;
  });
  double lowest = 1.0;
  for (const double c : bend_) lowest = std::min(lowest, c);
  return std::acos(std::clamp(lowest, -1.0, 1.0));
}

}  // namespace sutura::engine::detail
