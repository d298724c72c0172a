#pragma once
// Deforming a triangle mesh so that prescribed vertices reach given positions and the rest
// follows smoothly (harmonic extension) or as rigidly as possible: how a join carries a flap
// along when its rim is drawn onto an incision (join placement OntoB).
#include <vector>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine::detail {

/// Displacement of every vertex: `prescribed[v]` vertices keep `value[v]`; every other vertex
/// gets the weighted mean of its neighbours' displacements (a discrete harmonic field).
/// Weights are 1 / edge length: positive, so each free displacement is a convex combination
/// of its neighbours' and the field never overshoots the prescribed values (cotangent weights
/// turn negative on obtuse triangles and can). A connected part without a prescribed vertex
/// does not move. Solved by one sparse Cholesky factorisation of the free block (symmetric
/// positive definite: every free part reaches a prescribed vertex). Cost O(V^1.5) for a
/// surface mesh. Throws InvalidArgument on size mismatches.
std::vector<Vec3> harmonic_spread(const std::vector<Vec3>& positions,
                                  const std::vector<FaceIndices>& faces,
                                  const std::vector<bool>& prescribed,
                                  const std::vector<Vec3>& value);

/// As-rigid-as-possible placement (Sorkine & Alexa 2007): positions close to `positions`
/// up to a rotation per vertex neighbourhood, with `prescribed[v]` vertices at
/// positions[v] + value[v]. Alternates the best rotation of each neighbourhood (polar
/// decomposition of its edge covariance) with one linear solve (the matrix of
/// harmonic_spread, factorised once). The prescribed displacements are applied in `stages`
/// equal steps, `iterations` each, starting from the harmonic spread of the first: started
/// from the harmonic spread of the whole displacement, which squeezes a region turned by
/// more than about a quarter turn through itself, the iteration stays in that folded local
/// minimum. Where the prescribed vertices squeeze a region (a flap whose rim is drawn onto
/// a closed slit), the rigid fit keeps its edge lengths by lifting it out of the surface
/// instead of collapsing it. Cost: stages * iterations back-substitutions and 3x3 SVDs per
/// vertex. Throws InvalidArgument on size mismatches, iterations < 0 or stages < 1.
std::vector<Vec3> as_rigid_as_possible(const std::vector<Vec3>& positions,
                                       const std::vector<FaceIndices>& faces,
                                       const std::vector<bool>& prescribed,
                                       const std::vector<Vec3>& value, int iterations,
                                       int stages);

}  // namespace sutura::engine::detail
