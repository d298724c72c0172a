#pragma once
// Mesh files: import through assimp (STL, OBJ, PLY), export OBJ, PLY, STL.
#include <filesystem>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct ImportOptions {
  /// Vertices closer than weld_tolerance * (bounding-box diagonal) are merged into one.
  /// STL stores every triangle's corners separately, so welding is what makes it a mesh.
  /// 0 (or anything below 1e-12) merges exact duplicates only. Dimensionless, >= 0.
  double weld_tolerance = 1e-6;
};

/// Reads a triangle mesh. All meshes of the file are merged, polygons are triangulated, and
/// points/lines are ignored; vertices are welded, unused vertices dropped.
/// Throws MeshIoError (kind Missing, Unreadable, UnsupportedFormat, Empty, NonFinite,
/// Degenerate or NonManifold) whose message names the file and the problem.
SurfaceMesh load_mesh(const std::filesystem::path& file, const ImportOptions& options = {});

/// Writes the mesh; the format follows the extension (.obj, .ply, .stl — binary STL).
/// Written to a temporary file in the same directory and renamed into place, so a failure
/// never leaves a half-written file. Throws MeshIoError (UnsupportedFormat, WriteFailed).
void save_mesh(const SurfaceMesh& mesh, const std::filesystem::path& file);

}  // namespace sutura::engine
