#pragma once
// Element-independent corotational (EICR) kinematics of a 3-node, 6-DOF triangle
// (private to engine/src/shell). Rankin & Nour-Omid (1988); Felippa & Haugen (2005),
// "A unified formulation of small-strain corotational finite elements: I. Theory",
// CMAME 194, 2285-2335 (below: FH).
//
// Frame. The current element frame T = [e1 e2 e3] has e3 along the normal of the current
// corners and its in-plane axes chosen so that the current local corner coordinates x_a best
// fit the rest local coordinates X_a in the least-squares sense: sum_a (X_a x x_a).e3 = 0 with
// sum_a X_a.x_a > 0 (the "best fit" CR-frame alignment discussed by FH). It does not depend on corner numbering,
// removes all rigid in-plane rotation from the deformational displacements (important for the
// drilling freedoms), and coincides with element_frame() of the rest corners at rest. The rest
// local coordinates X_a are taken in element_frame(rest corners), centroid at the origin.
//
// Deformational DOFs d (18; per corner [u (3), theta (3)], local components):
//   u_a = x_a - X_a, and
//   theta_a = log(T^T D_a Q_a^T)  (ElementRest::Q: rest triads in the rest element frame).
// The element energy is 1/2 d^T K d with K the 18x18 linear local stiffness, which splits
// into the ANDES membrane block on (u_x, u_y, theta_z) and the DKT bending block on
// (w, theta_x, theta_y). The normal translations w_a = u_a.e3 vanish identically (all corners
// lie in the frame's plane, before and after any variation: the rows of B below for w are
// zero by the shape-function identity sum_b N_b(x_a) = delta_ab), so only the 6x6 rotational
// part of the bending block enters, and the bending shear forces drop out of the gradient.
// Variations, for translational increments dx_a and spatial spins dw_a (both in local
// components, xi_a = T^T dx_a, eta_a = T^T dw_a):
//   frame spin   domega = G xi      (G: FH's spin-fitter for this frame, 3x9),
//   du_a     = xi_a - mean(xi) + x_a x (G xi)        (FH's projector P on translations),
//   dtheta_a = H_a (eta_a - G xi),  H_a = J_l^{-1}(theta_a)   (FH's H matrix).
// Gradient: g = T-rotated B^T f with f = K d and B = d(d)/d(xi, eta) (FH's P^T H^T f).
// Tangent: linearisation of that gradient, i.e. of g at the state perturbed by the increment
// (x + dx, exp([dw]x) D): B^T K B (material) plus the geometric terms FH call K_GR (rotation of
// the frame carrying the gradient), K_GP (derivative of the projector, including the
// derivative of G), and K_M (derivative of H^T m). The result is the exact derivative of the
// gradient as defined in shell_model.hpp; it is nonsymmetric only in the diagonal corner
// rotation blocks (by -1/2 [g_w]x), so its symmetric part is the exact Hessian of the energy
// in the spin parametrisation.
#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine {

using Mat18 = Eigen::Matrix<double, 18, 18>;
using Vec18 = Eigen::Matrix<double, 18, 1>;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Rest geometry of one element in its own rest frame.
struct LocalRest {
  std::array<Eigen::Vector2d, 3> X;  ///< rest local in-plane coordinates, centroid at origin, mm
  std::array<Quat, 3> Q;             ///< rest triads in the rest element frame
  double area = 0.0;                 ///< rest area, mm^2 (<= 0 for a degenerate/flipped rest)
};

LocalRest make_local_rest(const ElementRest& rest);

/// The parts of the 18x18 local stiffness that act on d (see above).
struct LocalStiffness {
  Mat9 membrane;  ///< per corner (u_x, u_y, theta_z), N/mm, N, N*mm
  Mat6 bending;   ///< per corner (theta_x, theta_y), N*mm
};

/// The current configuration of one element seen from its corotated frame.
struct CorotatedElement {
  Eigen::Matrix3d T;                 ///< current frame, columns e1 e2 e3
  std::array<Eigen::Vector2d, 3> x;  ///< current local in-plane coordinates, mm
  Vec9 dm;  ///< membrane deformational DOFs, per corner (u_x, u_y, theta_z)
  Vec6 db;  ///< bending deformational DOFs, per corner (theta_x, theta_y)
};

/// Frame and deformational DOFs of the element with current corners `x` and triads `D`.
/// Cost: about 300 flops.
CorotatedElement corotate(const LocalRest& rest, const std::array<Eigen::Vector3d, 3>& x,
                          const std::array<Quat, 3>& D);

/// Local forces conjugate to d: membrane fm = K_m dm, bending fb = K_b db.
struct LocalForces {
  Vec9 fm;
  Vec6 fb;
};

/// Gradient `g` (18, global components, per corner [translation (3), spin (3)]) of the energy
/// 1/2 d^T K d; with `tangent` also its consistent tangent (global components; `symmetric`
/// keeps the symmetric part). Cost: gradient ~400 flops, tangent ~12k flops.
void corotational_gradient(const LocalRest& rest, const CorotatedElement& e,
                           const LocalStiffness& K, const LocalForces& f, Vec18& g,
                           Mat18* tangent, bool symmetric);

}  // namespace sutura::engine
