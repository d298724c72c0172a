#pragma once
// Bitwise equality of the inputs the rest-data memos are keyed by (private to
// engine/src/shell): element_stiffness_cache.hpp (model 1), discrete_rest_cache.hpp (model 2).
// Bitwise, not numeric: an entry is reused only for exactly the inputs it was built from, so a
// memo never changes a result; a NaN input never matches, so it is rebuilt (and reported) on
// every call.
#include "sutura/engine/shell/material.hpp"
#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine {

inline bool same_bits(const ElementRest& a, const ElementRest& b) {
  for (int k = 0; k < 3; ++k)
    if (a.X[k] != b.X[k] || a.Q[k].coeffs() != b.Q[k].coeffs()) return false;
  return true;
}

// A new material field must be compared here too.
static_assert(sizeof(ShellMaterial) == 5 * sizeof(double), "compare every ShellMaterial field");
inline bool same_bits(const ShellMaterial& a, const ShellMaterial& b) {
  return a.youngs_modulus == b.youngs_modulus && a.poisson_ratio == b.poisson_ratio &&
         a.thickness == b.thickness && a.density == b.density &&
         a.drilling_factor == b.drilling_factor;
}

}  // namespace sutura::engine
