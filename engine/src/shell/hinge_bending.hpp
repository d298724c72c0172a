#pragma once
// Bending energy of one face from the dihedral-angle changes of its three hinges (Model 2).
//
// Discrete shape operator (Grinspun, Gingold, Reisman, Zorin 2006, "Computing discrete shape
// operators on general meshes"; the mid-edge form of libshell / Tamstorf & Grinspun 2013 with
// bisecting mid-edge normals): with dtheta_k the change of the dihedral angle across half-edge
// k of the face (corner k -> k+1), rest edge vectors e_k, rest altitudes h_k = 2A/|e_k| and
// in-plane unit edge normals b_k, the change of curvature on the face is
//   K = sum_k (dtheta_k / h_k) b_k b_k^T.
// The Kirchhoff plate energy density D/2 [ nu tr(K)^2 + (1-nu) tr(K^2) ]
// (D = E t^3 / (12 (1 - nu^2)); mm, MPa => N*mm), integrated over the rest area A, gives
//   W = 1/2 dtheta^T C dtheta,
//   C_ij = D / (4A) [ nu |e_i||e_j| + (1-nu) (e_i . e_j)^2 / (|e_i||e_j|) ],
// a per-face hinge energy whose coefficients (diagonal D |e|^2/(4A), cf. the |e|^2/A weight
// of Grinspun et al. 2003) are those of the plate, including Poisson and twist coupling.
//
// Accuracy: exact for every constant curvature field where the two faces of each hinge form a
// parallelogram (the bisector is then the true normal at the edge midpoint), and for bending
// about mesh lines on quad-split grids with either diagonal pattern (the linear cantilever is
// exact); close on near-equilateral (Delaunay) meshes (simply supported circular plate: 0.998
// of the analytic deflection at 10k faces). Where neighbours are mirror images (alternating
// diagonals) twist is seen by the diagonal hinges only and counted about twice, so biaxial or
// twisting states come out too stiff (simply supported square plate: 0.61 of Navier's
// deflection at 64x64 cells, 1.0003 with uniform diagonals). Inverting the 6-node stencil's
// exact fold map instead is consistent on every mesh but has soft spurious modes on that mesh.
//
// Boundary edges have no hinge: their angle change is a free variable minimised out of W (the
// natural free-edge condition, zero normal moment), i.e. C is replaced by its Schur complement
// S on the interior hinges. All coefficients come from the rest triangle only.
// Cost per face: ~200 flops.
#include <array>

#include <Eigen/Core>

#include "sutura/engine/mesh.hpp"
#include "sutura/engine/shell/material.hpp"

namespace sutura::engine::dshell {

struct FaceBending {
  /// W = 1/2 dtheta^T S dtheta on the interior hinges (rows/columns of boundary edges are 0),
  /// N*mm/rad^2.
  Eigen::Matrix3d S;
  /// Maps interior hinge-angle changes to all three, the boundary ones at their minimiser.
  Eigen::Matrix3d P;
  Eigen::Vector3d inv_height;  ///< 1 / h_k, 1/mm
  Eigen::Matrix3d cos2;        ///< (b_i . b_j)^2 = (e_i . e_j)^2 / (|e_i|^2 |e_j|^2)
};

/// Bending data of a face with rest corners X; `interior[k]`: half-edge k has a hinge.
FaceBending make_face_bending(const std::array<Vec3, 3>& X, const ShellMaterial& m,
                              const std::array<bool, 3>& interior);

/// Largest |principal value| of the curvature change K (1/mm) for the interior hinge-angle
/// changes `dtheta` (boundary entries ignored).
double max_curvature_change(const FaceBending& b, const Eigen::Vector3d& dtheta);

}  // namespace sutura::engine::dshell
