#pragma once
// Penalty contact between separate objects (aorta against pulmonary artery): a vertex-triangle
// energy that keeps the surfaces of different objects at least about an activation distance
// apart, added to a ShellSystem as an EnergyTerm.
//
// Energy: for every vertex v of one surface and every triangle T of another surface at
// unsigned distance d = dist(x_v, T) below the activation distance d^ (both directions: A's
// vertices against B's triangles and B's vertices against A's),
//   E = sum A_v psi(d),   psi(d) = kappa / (3 d^) (d^ - d)^3   for d < d^, 0 otherwise,
// with A_v the vertex's rest area (one third of its adjacent rest face areas in its surface).
// psi, psi' and psi'' vanish at d = d^, so the energy is C2 in d where pairs switch on; the
// pressure law is p(d) = -psi'(d) = kappa (d^ - d)^2 / d^, i.e. kappa d^ at touching. Across
// the triangle's feature regions (face / edge / vertex) the distance is C1, so E is C1 there.
// Near a vertex or edge of the other surface several triangles report the same closest point,
// so the effective stiffness there is a few times kappa (continuous, conservative).
//
// Limitations: vertex-triangle pairs only (no edge-edge term: edges of coarse meshes may still
// cross without a vertex passing a triangle); a penalty, not a barrier: contact pressure above
// kappa d^, or a Newton step that carries a vertex past a triangle in one go (no continuous
// collision detection), lets surfaces pass. Use load steps and kappa d^ well above the
// expected contact pressure. Self-contact of one surface is not handled.
//
// Determinism: the broad phase (uniform grid) is rebuilt per evaluation, candidates are
// visited in triangle order per vertex, pairs are evaluated in parallel into per-vertex slots
// and summed sequentially in vertex order: results are bit-identical run to run and for any
// number of threads.
#include <vector>

#include "sutura/engine/sim/energy_term.hpp"
#include "sutura/engine/sim/point_triangle_distance.hpp"

namespace sutura::engine {

struct ContactParams {
  /// Activation distance d^, mm, > 0: surfaces of different objects are kept about this far
  /// apart (mid-surface to mid-surface), so use about half the sum of the two wall
  /// thicknesses. Pairs farther apart contribute exactly nothing.
  double distance = 0.5;
  /// Penalty stiffness kappa, N/mm^3 (MPa per mm), > 0: contact pressure kappa (d^ - d)^2 / d^
  /// per vertex-triangle pair, kappa d^ at touching. The default resists 0.5 MPa (3750 mmHg)
  /// at d^ = 0.5 mm, far above blood pressure (80 mmHg = 0.0107 MPa).
  double stiffness = 1.0;
  /// Project each pair's 12x12 Hessian onto the positive semi-definite cone (negative
  /// eigenvalues clamped to zero). The exact Hessian of a repelling point force is indefinite
  /// (tangential stiffness psi'(d)/d < 0); the projected one keeps the tangent SPD for
  /// Cholesky at the price of Newton converging less than quadratically while pairs are
  /// active. The gradient is exact either way.
  bool project_hessian = true;
};

/// Throws InvalidArgument naming the field if a parameter is out of range or not finite.
void validate(const ContactParams& p);

/// One contact body: faces of the system's problem (ShellProblem::faces). Its vertices are
/// the nodes these faces use; different surfaces must not share nodes.
struct ContactSurface {
  std::vector<FaceId> faces;
};

/// A vertex-triangle pair within the activation distance.
struct ContactPair {
  std::size_t node = 0;  ///< the vertex (system node)
  FaceId face;           ///< the triangle (problem face) of another surface
  TriangleFeature feature = TriangleFeature::Face;  ///< where the closest point lies
  double distance = 0.0;                            ///< mm
};

class ContactTerm final : public EnergyTerm {
 public:
  /// Copies the surfaces' triangles and the vertices' rest areas (from problem.rest) out of
  /// `problem`; keeps no reference to it. Throws InvalidArgument for fewer than two surfaces,
  /// an empty surface, a face id out of range, a node shared by two surfaces, an incomplete
  /// problem, or invalid params. Cost O(F).
  ContactTerm(const ShellProblem& problem, const std::vector<ContactSurface>& surfaces,
              const ContactParams& params);

  /// See EnergyTerm. Acts on the translational DOFs only. Throws InvalidArgument when the
  /// state has fewer positions than a surface's largest node id needs. Cost: O(V + F) for the
  /// broad phase plus O(pairs) (about 10^4 flops per pair with the Hessian).
  double add_energy_gradient_hessian(const ShellState& s, int dofs_per_node, Eigen::VectorXd& g,
                                     Triplets* K) const override;

  /// Every pair closer than the activation distance at `s`, ordered by vertex (surface order,
  /// then node id) and then by triangle (surface order, then face order). For reports, drawing
  /// and tests. Same cost as the broad phase.
  [[nodiscard]] std::vector<ContactPair> pairs(const ShellState& s) const;

  [[nodiscard]] const ContactParams& params() const { return params_; }

 private:
  struct Vertex {
    std::int32_t node;
    std::int32_t surface;
    double area;  // mm^2, rest
  };
  struct Triangle {
    FaceIndices nodes;
    std::int32_t surface;
    FaceId face;
  };
  struct Hit {
    std::int32_t triangle;  // index into triangles_
    PointTriangleClosest closest;
  };
  // Broad and narrow phase: per vertex (index into vertices_), its triangles within d^.
  [[nodiscard]] std::vector<std::vector<Hit>> search(const ShellState& s) const;

  std::vector<Vertex> vertices_;
  std::vector<Triangle> triangles_;
  std::int32_t max_node_ = -1;
  ContactParams params_;
};

}  // namespace sutura::engine
