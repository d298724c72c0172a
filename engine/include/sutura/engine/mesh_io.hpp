#pragma once
// Mesh files: import through assimp (STL, OBJ, PLY), export OBJ, PLY, STL.
#include <cstddef>
#include <filesystem>

#include "sutura/engine/mesh.hpp"

namespace sutura::engine {

struct ImportOptions {
  /// Vertices closer than weld_tolerance * (bounding-box diagonal) are merged into one.
  /// STL stores every triangle's corners separately, so welding is what makes it a mesh.
  /// 0 (or anything below 1e-12) merges exact duplicates only. Dimensionless, >= 0.
  double weld_tolerance = 1e-6;
  /// The most triangles the file may hold; 0 for no limit. Counted before the file is parsed
  /// (the count of a binary STL, the face element of a PLY header, facets of an ASCII STL
  /// and the triangles of an OBJ's polygons in one streamed pass over the bytes), so a file
  /// far above the limit is refused in O(size) time and O(1) memory.
  std::size_t max_faces = 0;
};

/// Reads a triangle mesh. All meshes of the file are merged, polygons are triangulated, and
/// points/lines are ignored; vertices are welded, unused vertices dropped.
/// Throws MeshIoError (kind Missing, Unreadable, UnsupportedFormat, Empty, NonFinite,
/// Degenerate, NonManifold or TooLarge) whose message names the file and the problem.
SurfaceMesh load_mesh(const std::filesystem::path& file, const ImportOptions& options = {});

/// Writes the mesh; the format follows the extension (.obj, .ply, .stl — binary STL).
/// Written to a temporary file in the same directory and renamed into place, so a failure
/// never leaves a half-written file. Throws MeshIoError (UnsupportedFormat, WriteFailed).
void save_mesh(const SurfaceMesh& mesh, const std::filesystem::path& file);

}  // namespace sutura::engine
