#include "sutura/engine/anatomy/aortic_arch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "arch_layout.hpp"
#include "sutura/engine/errors.hpp"
#include "vessel_surface.hpp"

namespace sutura::engine {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void require(bool ok, const char* field, const std::string& problem, double value) {
  if (!ok) throw InvalidArgument(std::string("arch: ") + field + ": " + problem + ", got " + num(value));
}

void require_range(double value, double lo, double hi, const char* field) {
  require(std::isfinite(value) && value >= lo && value <= hi, field,
          "must be in [" + num(lo) + ", " + num(hi) + "]", value);
}

}  // namespace

void validate(const ArchParams& p) {
  // Diameters: neonatal vessels are a few mm; the ranges only exclude nonsense.
  require_range(p.ascending_diameter, 2.0, 40.0, "ascending_diameter");
  require_range(p.proximal_arch_diameter, 2.0, 40.0, "proximal_arch_diameter");
  require_range(p.distal_arch_diameter, 2.0, 40.0, "distal_arch_diameter");
  require_range(p.isthmus_diameter, 2.0, 40.0, "isthmus_diameter");
  require_range(p.descending_diameter, 2.0, 40.0, "descending_diameter");
  require_range(p.ascending_length, 2.0, 100.0, "ascending_length");
  require_range(p.arch_tilt_deg, 0.0, 90.0, "arch_tilt_deg");
  require_range(p.descending_length, 5.0, 200.0, "descending_length");
  // The arch must bend around its own lumen: radius of curvature above the largest radius.
  const double widest = std::max({p.ascending_diameter, p.proximal_arch_diameter,
                                  p.distal_arch_diameter, p.isthmus_diameter,
                                  p.descending_diameter}) / 2;
  require(std::isfinite(p.arch_radius) && p.arch_radius > 1.2 * widest && p.arch_radius <= 100.0,
          "arch_radius", "must exceed 1.2 x the largest aortic radius and be at most 100", p.arch_radius);

  require_range(p.coarctation_fraction, 0.2, 1.0, "coarctation_fraction");
  require(p.coarctation_fraction * p.descending_diameter < p.isthmus_diameter ||
              p.coarctation_fraction == 1.0,
          "coarctation_fraction",
          "narrowest diameter (fraction x descending_diameter) must be below isthmus_diameter",
          p.coarctation_fraction);
  require_range(p.coarctation_length, 1.0, 20.0, "coarctation_length");

  require(std::isfinite(p.innominate_angle_deg) && p.innominate_angle_deg > 0.0,
          "innominate_angle_deg", "must be greater than 0", p.innominate_angle_deg);
  require(std::isfinite(p.carotid_angle_deg) && p.carotid_angle_deg > p.innominate_angle_deg,
          "carotid_angle_deg", "must be greater than innominate_angle_deg", p.carotid_angle_deg);
  require(std::isfinite(p.subclavian_angle_deg) && p.subclavian_angle_deg > p.carotid_angle_deg &&
              p.subclavian_angle_deg < 180.0,
          "subclavian_angle_deg", "must be greater than carotid_angle_deg and below 180",
          p.subclavian_angle_deg);
  require_range(p.lsa_diameter, 1.0, 20.0, "lsa_diameter");
  require_range(p.innominate_diameter, 1.0, 20.0, "innominate_diameter");
  require_range(p.carotid_diameter, 1.0, 20.0, "carotid_diameter");
  // A branch must reach out of the aorta: longer than the local aortic radius plus its own.
  require(std::isfinite(p.lsa_length) && p.lsa_length > widest + p.lsa_diameter && p.lsa_length <= 100.0,
          "lsa_length", "must exceed the largest aortic radius + lsa_diameter and be at most 100", p.lsa_length);
  require(std::isfinite(p.innominate_length) && p.innominate_length > widest + p.innominate_diameter &&
              p.innominate_length <= 100.0,
          "innominate_length", "must exceed the largest aortic radius + innominate_diameter and be at most 100",
          p.innominate_length);
  require(std::isfinite(p.carotid_length) && p.carotid_length > widest + p.carotid_diameter &&
              p.carotid_length <= 100.0,
          "carotid_length", "must exceed the largest aortic radius + carotid_diameter and be at most 100",
          p.carotid_length);

  // The narrowing starts beyond the LSA ostium and ends 5 mm before the descending end.
  const double arch_rest = p.arch_radius * (180.0 - p.subclavian_angle_deg) * std::numbers::pi / 180.0;
  const double half = p.coarctation_length / 2;
  require(std::isfinite(p.coarctation_offset) && p.coarctation_offset >= half + p.lsa_diameter / 2,
          "coarctation_offset", "must be at least coarctation_length / 2 + lsa_diameter / 2",
          p.coarctation_offset);
  require(p.coarctation_offset + half + 5.0 <= arch_rest + p.descending_length, "coarctation_offset",
          "puts the coarctation within 5 mm of the descending end; lengthen descending_length",
          p.coarctation_offset);

  require_range(p.pulmonary_trunk_diameter, 2.0, 40.0, "pulmonary_trunk_diameter");
  require_range(p.pulmonary_branch_diameter, 1.0, 40.0, "pulmonary_branch_diameter");
  require(p.pulmonary_branch_diameter < p.pulmonary_trunk_diameter, "pulmonary_branch_diameter",
          "must be below pulmonary_trunk_diameter", p.pulmonary_branch_diameter);
  require(std::isfinite(p.pulmonary_branch_length) &&
              p.pulmonary_branch_length > p.pulmonary_trunk_diameter / 2 + 2.0 &&
              p.pulmonary_branch_length <= 100.0,
          "pulmonary_branch_length", "must exceed pulmonary_trunk_diameter / 2 + 2 and be at most 100",
          p.pulmonary_branch_length);
  require_range(p.pulmonary_gap, 0.5, 20.0, "pulmonary_gap");

  require_range(p.junction_blend, 0.2, 3.0, "junction_blend");
  require_range(p.target_edge_length, 0.2, 2.0, "target_edge_length");
  // At least ~6 edges around the narrowest lumen: L <= r_min (2 pi r / L >= 6.28).
  const double narrowest =
      std::min({p.coarctation_fraction * p.descending_diameter, p.lsa_diameter,
                p.head_neck_branches ? std::min(p.innominate_diameter, p.carotid_diameter) : 1e9,
                p.pulmonary_branch_diameter}) / 2;
  require(p.target_edge_length <= narrowest, "target_edge_length",
          "must be at most the narrowest lumen radius (" + num(narrowest) + " mm)",
          p.target_edge_length);
}

ArchAnatomy generate_arch(const ArchParams& params) {
  validate(params);
  anatomy::ArchLayout layout = anatomy::layout_arch(params);
  ArchAnatomy out;
  const anatomy::VesselField aorta(layout.aorta.curves, params.junction_blend);
  const anatomy::VesselField pulmonary(layout.pulmonary.curves, params.junction_blend);
  out.aorta = anatomy::vessel_surface(aorta, layout.aorta.ends, anatomy::kEndExtension,
                                      params.target_edge_length);
  out.pulmonary = anatomy::vessel_surface(pulmonary, layout.pulmonary.ends,
                                          anatomy::kEndExtension, params.target_edge_length);
  out.landmarks = std::move(layout.landmarks);
  out.landmarks.centrelines = layout.aorta.centrelines;
  out.landmarks.centrelines.insert(out.landmarks.centrelines.end(),
                                   layout.pulmonary.centrelines.begin(),
                                   layout.pulmonary.centrelines.end());
  out.landmarks.aorta_ends = layout.aorta.ends;
  out.landmarks.pulmonary_ends = layout.pulmonary.ends;
  return out;
}

}  // namespace sutura::engine
