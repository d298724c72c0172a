#pragma once
// Centrelines, radius profiles and landmarks of the aortic-arch model (no meshing).
#include <vector>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "vessel_field.hpp"

namespace sutura::engine::anatomy {

/// One vessel object ready for surface generation: its curves (open ends extended by
/// `kEndExtension` so the implicit tube runs straight through each cutting plane) and ends.
struct VesselLayout {
  std::vector<Curve> curves;
  std::vector<VesselEnd> ends;
  std::vector<Centreline> centrelines;
};

/// mm the implicit tubes continue beyond each open end before their rounded tips.
inline constexpr double kEndExtension = 2.0;

struct ArchLayout {
  VesselLayout aorta;
  VesselLayout pulmonary;
  ArchLandmarks landmarks;  ///< complete except the end lists, which are in the layouts
};

/// Lays out the model for validated params. Throws InvalidArgument ("pulmonary_gap", or the
/// branch names) when the pulmonary artery comes closer to the aorta than pulmonary_gap or two
/// arch branches come closer than 0.5 mm to each other outside the aorta. Cost O(points^2)
/// for these checks, a few ms.
ArchLayout layout_arch(const ArchParams& p);

}  // namespace sutura::engine::anatomy
