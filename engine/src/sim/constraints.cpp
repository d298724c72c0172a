#include "sutura/engine/sim/constraints.hpp"

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

DofMask parse_dofs(const std::vector<std::string>& names) {
  DofMask m = 0;
  for (const auto& n : names) {
    if (n == "ux") m |= kUx;
    else if (n == "uy") m |= kUy;
    else if (n == "uz") m |= kUz;
    else if (n == "rx") m |= kRx;
    else if (n == "ry") m |= kRy;
    else if (n == "rz") m |= kRz;
    else if (n == "translations") m |= kTranslations;
    else if (n == "rotations") m |= kRotations;
    else if (n == "all") m |= kAllDofs;
    else
      throw InvalidArgument("unknown degree of freedom '" + n +
                            "' (ux, uy, uz, rx, ry, rz, translations, rotations, all)");
  }
  if (m == 0) throw InvalidArgument("no degree of freedom given");
  return m;
}

void Constraints::fix(const std::vector<VertexId>& nodes, DofMask dofs, std::size_t num_nodes) {
  if (fixed.size() < num_nodes) fixed.resize(num_nodes, 0);
  for (VertexId v : nodes) {
    if (v.index() >= num_nodes)
      throw InvalidArgument("constraint on vertex " + std::to_string(v.value) +
                            " out of range (" + std::to_string(num_nodes) + " vertices)");
    fixed[v.index()] |= dofs;
  }
}

}  // namespace sutura::engine
