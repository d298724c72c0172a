#pragma once
// Per-degree-of-freedom constraints: a fixed DOF keeps its value from the start of the run
// (zero increment). Bits: ux uy uz rx ry rz.
#include <cstdint>
#include <string>
#include <vector>

#include "sutura/engine/ids.hpp"

namespace sutura::engine {

using DofMask = std::uint8_t;
inline constexpr DofMask kUx = 1, kUy = 2, kUz = 4, kRx = 8, kRy = 16, kRz = 32;
inline constexpr DofMask kTranslations = kUx | kUy | kUz;
inline constexpr DofMask kRotations = kRx | kRy | kRz;
inline constexpr DofMask kAllDofs = kTranslations | kRotations;

/// Parses DOF names: "ux" "uy" "uz" "rx" "ry" "rz", "translations", "rotations", "all".
/// Throws InvalidArgument naming an unknown entry.
DofMask parse_dofs(const std::vector<std::string>& names);

struct Constraints {
  std::vector<DofMask> fixed;  ///< per node; empty or shorter = free

  void fix(const std::vector<VertexId>& nodes, DofMask dofs, std::size_t num_nodes);
  [[nodiscard]] bool is_fixed(std::size_t node, int dof) const {
    return node < fixed.size() && (fixed[node] >> dof) & 1u;
  }
};

}  // namespace sutura::engine
