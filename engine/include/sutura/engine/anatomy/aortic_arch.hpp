#pragma once
// Synthetic neonatal aortic arch with a discrete coarctation, and the pulmonary artery beside
// it — the test anatomy for surgery sessions while no patient data is available offline.
// Model, dimensions and sources: docs/anatomy.md.
//
// Frame (mm): origin at the centre of the aortic root's open end; +x patient's left,
// +y posterior, +z superior (LPS). The arch centreline lies in a vertical plane turned
// `arch_tilt_deg` from the sagittal plane towards the patient's left, so the arch runs from
// anterior-right (ascending aorta) to posterior-left (descending aorta).
//
// Surfaces: each vessel object is the zero set of a smooth union of "generalised tubes" around
// its centrelines (docs/anatomy.md), extracted by marching tetrahedra, cut open by planes at
// its ends and remeshed isotropically onto the exact implicit surface (CGAL). Each object is
// one connected, consistently oriented 2-manifold with outward normals, smooth branch
// junctions and one planar boundary loop per open end. Deterministic: the same parameters
// give bit-identical meshes.
#include <string>
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

/// Target edge lengths of the shipped assets (assets/anatomy/): about 4k and 20k aorta faces.
inline constexpr double kArchCoarseEdgeLength = 1.1;   // mm
inline constexpr double kArchFineEdgeLength = 0.52;    // mm

/// Parameters of the arch model; defaults describe a ~3 kg neonate (docs/anatomy.md).
/// All lengths and diameters in mm, angles in degrees.
struct ArchParams {
  // --- aorta lumen diameters along the path (blended smoothly between landmarks) -----------
  double ascending_diameter = 8.0;      ///< root and ascending aorta
  double proximal_arch_diameter = 7.0;  ///< transverse arch at the left common carotid origin
  double distal_arch_diameter = 6.0;    ///< distal arch at the left subclavian origin
  double isthmus_diameter = 5.5;        ///< isthmus, just distal to the left subclavian
  double descending_diameter = 6.5;     ///< descending aorta beyond the coarctation

  // --- aorta path ---------------------------------------------------------------------------
  double ascending_length = 15.0;   ///< root to the start of the arch, along +z
  double arch_radius = 9.0;         ///< radius of curvature of the (half-circle) arch centreline
  double arch_tilt_deg = 35.0;      ///< arch plane turned from sagittal towards the left, [0, 90]
  double descending_length = 30.0;  ///< end of the arch down to the open descending end

  // --- coarctation (discrete narrowing, raised-cosine profile) ------------------------------
  /// Narrowest lumen diameter as a fraction of descending_diameter (the coarctation index),
  /// in [0.2, 1]; 1 means no narrowing.
  double coarctation_fraction = 0.45;
  double coarctation_offset = 7.0;  ///< centreline distance, LSA origin to coarctation centre
  double coarctation_length = 4.0;  ///< full length of the narrowing along the centreline

  // --- arch branches: straight tubes from the aortic centreline, tilted out of the arch ------
  /// Positions along the arch as the angle on the arch half-circle, 0 = top of the ascending
  /// aorta, 180 = start of the descending aorta; innominate < carotid < subclavian.
  double innominate_angle_deg = 40.0;
  double carotid_angle_deg = 80.0;
  double subclavian_angle_deg = 120.0;
  double lsa_diameter = 3.8;       ///< left subclavian artery (always generated)
  double lsa_length = 14.0;        ///< from the aortic centreline to the open end
  /// Innominate (brachiocephalic) and left common carotid arteries. Default on: the arch then
  /// has its three normal branches; off leaves only the left subclavian artery.
  bool head_neck_branches = true;
  double innominate_diameter = 5.0;
  double innominate_length = 12.0;
  double carotid_diameter = 3.6;
  double carotid_length = 14.0;

  // --- pulmonary artery (separate object, left-anterior of the ascending aorta) -------------
  double pulmonary_trunk_diameter = 9.0;   ///< main pulmonary artery
  double pulmonary_branch_diameter = 5.0;  ///< left and right pulmonary arteries
  double pulmonary_branch_length = 10.0;   ///< bifurcation to each open end
  /// Required clearance between pulmonary and aortic walls (checked on the centrelines).
  double pulmonary_gap = 2.0;

  // --- surface ------------------------------------------------------------------------------
  double junction_blend = 1.5;       ///< width of the smooth union at branch junctions, [0.2, 3]
  double target_edge_length = kArchCoarseEdgeLength;  ///< remeshing target, [0.2, 2]
};

/// Centreline with the lumen radius at each point (points about 0.5 mm apart).
struct Centreline {
  std::string name;
  std::vector<Vec3> points;
  std::vector<double> radii;
};

/// An open vessel end: its boundary loop is the circle of `radius` around `centre` in the
/// plane with unit `normal`, which points out of the vessel.
struct VesselEnd {
  std::string name;
  Vec3 centre;
  Vec3 normal;
  double radius;
};

/// Positions surgery sessions need (mm, in the frame above).
struct ArchLandmarks {
  /// "aorta" (root -> descending end, through the coarctation), "innominate",
  /// "left_common_carotid" (if generated), "left_subclavian" (aortic centreline -> open end),
  /// "pulmonary_trunk", "left_pulmonary", "right_pulmonary".
  std::vector<Centreline> centrelines;
  Vec3 coarctation_centre;           ///< on the aortic centreline, at the narrowest section
  Vec3 coarctation_axis;             ///< unit centreline tangent there, towards the descending end
  double coarctation_min_radius;     ///< lumen radius at the centre
  double coarctation_length;         ///< full length of the narrowing
  Vec3 lsa_origin;                   ///< where the LSA axis leaves the aortic wall (ostium centre)
  Vec3 lsa_axis;                     ///< unit, from the aortic centreline towards the tip
  Vec3 lsa_tip;                      ///< centre of the LSA's open end
  double lsa_radius;
  std::vector<VesselEnd> aorta_ends;      ///< "ascending_root", "descending", then branch names
  std::vector<VesselEnd> pulmonary_ends;  ///< "pulmonary_root", "left_pulmonary", "right_pulmonary"
};

struct ArchAnatomy {
  SurfaceMesh aorta;      ///< aorta with its branches, one manifold
  SurfaceMesh pulmonary;  ///< pulmonary trunk with left and right branches, one manifold
  ArchLandmarks landmarks;
};

/// Throws InvalidArgument naming the first bad field and the problem (non-positive or
/// out-of-range value, branches out of order, coarctation not between the LSA and the end of
/// the descending aorta, resolution too coarse for the narrowest lumen).
void validate(const ArchParams& params);

/// Builds the anatomy. Validates `params` (see validate) and also throws InvalidArgument if
/// the layout makes the pulmonary artery come closer than `pulmonary_gap` to the aorta or two
/// arch branches touch. Cost: about 3 s at the coarse and 7 s at the fine asset resolution
/// (remeshing with exact projections dominates; single-threaded).
ArchAnatomy generate_arch(const ArchParams& params);

}  // namespace sutura::engine
