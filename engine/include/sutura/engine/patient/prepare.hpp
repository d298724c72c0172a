#pragma once
// Preparation of a segmentation export (CT/MRI, exported from 3D Slicer, Mimics, ITK-SNAP) for
// planning: a closed, dense, slightly noisy surface with flat end caps becomes an open vessel at
// simulation resolution with named ends. The steps, each deterministic:
//   0. the user's clip planes, if any (a resection beyond each plane);
//   1. keep the largest connected component (smaller ones are reported as dropped);
//   2. orient the faces outward (signed volume, open ends closed by fans);
//   3. find the flat end caps and open them (each becomes a named open end);
//   4. Taubin (lambda|mu) smoothing of the segmentation noise, every vertex's move bounded,
//      open ends and cap rims held;
//   5. isotropic remeshing to the target edge length (CGAL, the surgical remesher's whole-mesh
//      mode: vertices projected back onto the smoothed surface and the end loops);
//   6. measurement of the result: quality, and the Hausdorff distance to the input.
// Method, limits and validation: docs/patient-data.md.
#include <cstddef>
#include <utility>
#include <optional>
#include <string>
#include <vector>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/measure/hausdorff.hpp"
#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

/// Why a surface cannot be prepared. what() names the problem, its size and where it is (mm).
class PrepareError : public Error {
 public:
  enum class Kind {
    SeveralComponents,   ///< more than one component holds a large share of the area
    OpenHole,            ///< a boundary loop that is not a flat open end
    NoEnds,              ///< no flat cap and no open end: nothing to derive the vessel ends from
    SelfIntersecting,    ///< faces of the input cross each other
    EdgeLength,          ///< the target edge length is out of range for this vessel
    TooLarge,            ///< the result would hold too many faces
    Topology,            ///< opening the caps leaves a non-manifold surface
    Clip,                ///< a clip plane does not cut the vessel cleanly
  };
  PrepareError(Kind kind, const std::string& what) : Error(what), kind_(kind) {}
  [[nodiscard]] Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

/// The most faces prepare_vessel takes (its distance measurement samples every input face).
inline constexpr std::size_t kMaxPrepareInputFaces = 5'000'000;

/// A user's plane to clip an end at (the surgeon's choice where the vessel ends, e.g. a long
/// descending aorta or a branch that is not wanted): the surface is cut along the plane within
/// `radius` of `origin`, and the part on the side `normal` points to is removed, leaving a flat
/// open end. The removed part is the one holding the input's farthest vertex beyond the plane
/// within `radius` of `origin`.
struct PrepareClip {
  Vec3 origin = Vec3::Zero();   ///< mm, on the vessel's axis where it is to end
  Vec3 normal = Vec3::UnitZ();  ///< towards the part removed; need not be unit, must be non-zero
  double radius = 10.0;         ///< mm, > 0: only edges this near the origin are cut
};

struct PrepareParams {
  /// Applied first, in order, each to the result of the previous.
  std::vector<PrepareClip> clips;
  /// Target edge length of the result, mm. Default: 2 pi r / 16 for the smallest end radius r
  /// (16 edges around the narrowest end). Allowed: 6 to 64 edges around that end.
  std::optional<double> edge_length;
  /// Detect the caps and report them, but keep them closed (their rims stay sharp).
  bool keep_caps = false;
  /// Taubin smoothing iterations (each a lambda = 0.5 and a mu = -0.53 pass); 0 for none.
  int smoothing_iterations = 10;
  /// No vertex moves farther than this fraction of the target edge length in smoothing (the
  /// smoothing takes off noise, not shape).
  double smoothing_bound = 0.02;
  /// Remeshing iterations (split, collapse, flip, relax, project).
  int remesh_iterations = 5;
  /// Components of less than this fraction of the largest one's area are dropped; a larger
  /// second component is an error (which one is the vessel is the user's decision).
  double drop_area_fraction = 0.05;
  /// Faces meeting at more than this dihedral angle (degrees) bound a cap.
  double crease_angle_deg = 45.0;
  /// From this many faces on, the first coarsening of the remeshing (shortest edges collapsed
  /// to half the target) runs in two halves of the surface, on two threads when the compute
  /// threads allow; the result is the same on any thread count. Below the default, the halves
  /// would not pay for their cut (docs/performance.md).
  std::size_t coarsen_in_halves_from = 200'000;
  /// The most faces the result may hold: a target that would exceed it (estimated from the
  /// area) is refused before remeshing, and a result that does (the curvature refinement adds
  /// faces) after it.
  std::size_t max_faces = 2'000'000;
};

struct DroppedComponent {
  std::size_t faces = 0;
  double area = 0.0;  ///< mm^2
  Vec3 centroid = Vec3::Zero();
};

/// An open end of the prepared vessel (VesselEnd: name "end_1" ... by decreasing radius,
/// centre of its loop, unit normal out of the vessel, mean radius) and where it came from.
struct PreparedEnd {
  VesselEnd end;
  bool was_cap = false;        ///< a flat cap of the input (else an open end of the input)
  std::size_t cap_faces = 0;   ///< input faces of the cap
  double flatness = 0.0;       ///< mm: the largest distance of a rim vertex from the end plane
};

struct PrepareResult {
  SurfaceMesh vessel;                     ///< open (or capped, keep_caps), oriented outward
  std::vector<PreparedEnd> ends;
  std::vector<DroppedComponent> dropped;  ///< by decreasing area
  /// Per clip, in order: the faces and area (mm^2) it removed from the input.
  std::vector<std::pair<std::size_t, double>> clipped;
  std::size_t input_vertices = 0, input_faces = 0;
  bool flipped = false;          ///< the input was oriented inward and has been turned
  double edge_length = 0.0;      ///< mm, the target used
  bool edge_length_derived = false;  ///< from the smallest end (not given)
  double min_angle_deg = 0.0;    ///< of the result
  double min_edge = 0.0, max_edge = 0.0, mean_edge = 0.0;  ///< mm, of the result
  /// Result (a) against the input surface (b) without its caps and what the clips removed:
  /// a_to_b is how far the prepared surface strays from the segmentation.
  HausdorffDistance to_input;
  double hausdorff_spacing = 0.0;  ///< mm between its samples: a fifth of the target, or more
                                   ///< for a result so large that the samples would pass 16M
  /// Wall-clock seconds of each step, in order ("components", "self_intersections", "ends",
  /// "smoothing", "remeshing", "measuring"); the only part of the result that varies by run.
  std::vector<std::pair<std::string, double>> step_seconds;
};

/// Prepares `input` (welded; any orientation; at most kMaxPrepareInputFaces faces). Throws
/// PrepareError (kinds above) and InvalidArgument for parameters out of range. Cost: O(F log F) for the input's F faces plus
/// the remeshing, O(F_out * iterations * log F).
PrepareResult prepare_vessel(const SurfaceMesh& input, const PrepareParams& params = {});

/// Self-intersections of a surface: pairs of distinct faces that meet other than along the
/// edge or vertex they share (crossing, or touching where they share nothing), at most about
/// `max_pairs` of them (0: all), sorted. Faces of zero area are not reported. CGAL's
/// `self_intersections` with its box-intersection filter. Cost O(F log F + k).
std::vector<std::pair<FaceId, FaceId>> self_intersections(const SurfaceMesh& mesh,
                                                          std::size_t max_pairs);

}  // namespace sutura::engine
