#pragma once
// Dihedral angle of a hinge (two triangles sharing an edge), its exact first and second
// derivatives, and the rest dihedral angle taken from per-element rest data (Model 2).
//
// Hinge (a, b; c, d): face f = (a, b, c) holds the edge as a -> b, face g = (b, a, d) holds it
// as b -> a (both counter-clockwise, consistently oriented). With N_f = (b-a) x (c-a),
// N_g = (a-b) x (d-b) and e^ = (b-a)/|b-a|,
//   theta = atan2( e^ . (N_f x N_g), N_f . N_g )           in (-pi, pi],
// zero when flat, positive when the hinge folds away from the normals (convex seen from the
// normal side), independent of which face is called f. Cost: ~100 flops for theta, ~200 with
// the gradient, ~2500 with the Hessian.
#include <Eigen/Core>

#include "sutura/engine/shell/rest_state.hpp"

namespace sutura::engine::dshell {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

/// theta of the hinge at the given positions; optionally its gradient and Hessian w.r.t.
/// (a, b, c, d) (vertex-major, 12 entries). Gradient (Bridson et al. 2003, "Simulation of
/// clothing with folds and wrinkles"): with t_c, t_d the projections of c, d onto the edge,
///   dtheta/dc = -|e| N_f/|N_f|^2,  dtheta/dd = -|e| N_g/|N_g|^2,
///   dtheta/da = -(1-t_c) dtheta/dc - (1-t_d) dtheta/dd,
///   dtheta/db = -t_c dtheta/dc - t_d dtheta/dd.
/// The Hessian differentiates these expressions exactly (symmetrised against round-off).
/// Requires both triangles non-degenerate.
double dihedral_angle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, Vec12* grad,
                      Mat12* hess);

/// Rest dihedral angle of the hinge, from the rest data of its two faces only.
///
/// Definition: at a shared node i, face f's rest normal expressed in the node's rest frame is
/// nu_f = Q_f[k]^T e_z (k = corner of i in f; Q_f[k] = T_f^T D_i, T_f = element_frame(X_f)),
/// and the edge a -> b in that frame is Q_f[k]^T T_f^T (X_f[b] - X_f[a]); likewise for g. The
/// angle at node i is
///   theta_i = atan2( e^ . (nu_f x nu_g), nu_f . nu_g ),  e^ = unit(unit(e_f) + unit(e_g)),
/// i.e. the current-angle formula applied to the normals transported through the node frame.
/// The rest angle is the mean of theta_a and theta_b (taken modulo 2 pi around theta_a).
/// Only X_f and X_g relative to their own frames enter, so it does not depend on where each
/// face's X lies in space. For a rest state congruent with a state x (rest_from_state), it
/// equals the current theta of x up to round-off. `fa`, `fb` (`ga`, `gb`) are the corners of
/// a and b in f (in g).
double rest_dihedral_angle(const ElementRest& f, int fa, int fb, const ElementRest& g, int ga,
                           int gb);

}  // namespace sutura::engine::dshell
