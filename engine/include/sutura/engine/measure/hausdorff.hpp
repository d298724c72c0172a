#pragma once
// Hausdorff distance between two surfaces (the convergence study of the paper's Fig. 3.2:
// each result against the finest one).
#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct HausdorffDistance {
  double a_to_b = 0.0;     ///< mm: the largest distance from a point of A to the surface B
  double b_to_a = 0.0;     ///< mm: the same from B to A
  double symmetric = 0.0;  ///< mm: max(a_to_b, b_to_a)
  double mean_a_to_b = 0.0, mean_b_to_a = 0.0;  ///< mm: over the samples
  Vec3 a_to_b_at = Vec3::Zero();  ///< mm: the sample of A at a_to_b from B (the first such)
  Vec3 b_to_a_at = Vec3::Zero();  ///< mm: the sample of B at b_to_a from A
  std::size_t samples_a = 0, samples_b = 0;
};

/// Samples each surface deterministically (its vertices and, in every face, a barycentric
/// grid fine enough that no sample is farther than `spacing` mm from the next) and measures
/// each sample's distance to the other surface (exact closest point, AABB tree). A one-sided
/// value is a lower bound of the true one, short of it by at most `spacing`. `spacing` <= 0:
/// half the smaller of the two mean edge lengths. Throws InvalidArgument for an empty mesh or
/// more than 20,000,000 samples. Cost O((F_a + F_b) * n^2 * log F), n = edge / spacing; the
/// two sides run on two threads when the compute threads (compute_threads.hpp) are two or
/// more, with the same result.
HausdorffDistance hausdorff_distance(const SurfaceMesh& a, const SurfaceMesh& b,
                                     double spacing = 0.0);

}  // namespace sutura::engine
