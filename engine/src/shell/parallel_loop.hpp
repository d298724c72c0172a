#pragma once
// Parallel per-element and per-node loops of the shell models and the solvers (private to
// engine/src).
#include <cstddef>

namespace sutura::engine {

/// Below this many items (elements, hinges) a loop runs serially: the OpenMP fork/join costs
/// more than it saves.
constexpr std::size_t kParallelThreshold = 512;

/// Runs body(i) for i in [0, n), in parallel (static schedule) from kParallelThreshold items
/// on. Results do not depend on the thread count when every i writes only its own slots.
/// body must not throw: an exception must not leave an OpenMP region.
template <class Body>
void for_each_index(std::size_t n, Body&& body) {
  const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(static) if (n >= kParallelThreshold)
  for (std::ptrdiff_t i = 0; i < count; ++i) body(static_cast<std::size_t>(i));
}

}  // namespace sutura::engine
