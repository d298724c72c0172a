#pragma once
// Memo of model 1's rest-dependent element data (private to engine/src/shell).
//
// Why: the linear local stiffness (ANDES-OPT + DKT, about 0.9 us per element) and the local
// rest coordinates depend only on the element's rest geometry and material, yet a gradient
// evaluation (about 1.9 us per element) would rebuild them every call. Dynamics and Newton
// evaluate the same rest state many times, so keeping them halves the cost of a gradient.
//
// Contract: transparent. An entry is reused only when the element's rest corners, rest triads
// and material values are bitwise the ones it was built from; anything else (relaxation moving
// the rest state, a new mesh after an edit, another problem on the same model) rebuilds that
// entry with the same function, so results are bit-identical with or without the cache and the
// model stays a pure function of its inputs. Memory: about 1.3 kB per element.
//
// Threads: entry f is touched only by the thread evaluating element f. Whole calls are
// serialised by `mutex`; a caller that cannot take it (e.g. the GUI measuring while a solver
// runs in the background) computes without the cache instead of waiting.
#include <cstddef>
#include <mutex>
#include <vector>

#include "corotation.hpp"
#include "sutura/engine/shell/material.hpp"

namespace sutura::engine {

/// What an element's energy needs besides the current state.
struct ElementRestData {
  LocalRest rest;
  LocalStiffness K;
};

/// Builds the data of one element; returns false for a degenerate rest triangle (area below
/// 1e-12 of its squared longest edge), leaving K unset.
bool build_element_rest_data(const ElementRest& rest, const ShellMaterial& material,
                             ElementRestData& out);

class ElementStiffnessCache {
 public:
  /// Makes room for F elements (keeps entries that remain in range).
  void resize(std::size_t F);
  /// The data of element f for these inputs, rebuilt if they changed; nullptr for a degenerate
  /// rest triangle. Requires f < the size given to resize().
  const ElementRestData* get(std::size_t f, const ElementRest& rest, const ShellMaterial& material);

  std::mutex mutex;

 private:
  struct Entry {
    ElementRest key_rest;
    ShellMaterial key_material;
    ElementRestData data;
    bool built = false;       ///< key_* hold the inputs data was built from
    bool degenerate = false;  ///< build_element_rest_data returned false for them
  };
  std::vector<Entry> entries_;
};

}  // namespace sutura::engine
