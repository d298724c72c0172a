#include "element_stiffness_cache.hpp"

#include <algorithm>

#include "andes_membrane.hpp"
#include "dkt_bending.hpp"
#include "rest_key.hpp"

namespace sutura::engine {

bool build_element_rest_data(const ElementRest& rest, const ShellMaterial& m,
                             ElementRestData& out) {
  out.rest = make_local_rest(rest);
  const auto& X = out.rest.X;
  const double l2 = std::max({(X[1] - X[0]).squaredNorm(), (X[2] - X[1]).squaredNorm(),
                              (X[0] - X[2]).squaredNorm()});
  if (!(out.rest.area > 1e-12 * l2)) return false;
  out.K.membrane = andes_membrane_stiffness(X, m);
  // DKT's w rows and columns are dropped: the corotated normal translations vanish
  // identically (corotation.hpp).
  const Eigen::Matrix<double, 9, 9> Kb = dkt_bending_stiffness(X, m);
  constexpr int kRotation[6] = {1, 2, 4, 5, 7, 8};  // (theta_x, theta_y) of each corner
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) out.K.bending(i, j) = Kb(kRotation[i], kRotation[j]);
  return true;
}

void ElementStiffnessCache::resize(std::size_t F) { entries_.resize(F); }

const ElementRestData* ElementStiffnessCache::get(std::size_t f, const ElementRest& rest,
                                                  const ShellMaterial& material) {
  Entry& e = entries_[f];
  if (!e.built || !same_bits(e.key_rest, rest) || !same_bits(e.key_material, material)) {
    e.key_rest = rest;
    e.key_material = material;
    e.degenerate = !build_element_rest_data(rest, material, e.data);
    e.built = true;
  }
  return e.degenerate ? nullptr : &e.data;
}

}  // namespace sutura::engine
