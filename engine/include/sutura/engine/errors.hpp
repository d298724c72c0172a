#pragma once
// Typed exceptions of the engine (pmp-library style): callers catch the family they can handle,
// and every message names the object (file, operation) and the problem in words a user reads.
#include <stdexcept>
#include <string>

namespace sutura::engine {

/// Base of every error the engine throws on bad input.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Invalid parameters passed to an engine operation (negative radius, too few segments, ...).
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// The connectivity or geometry handed to the mesh is not a valid manifold triangle mesh.
class TopologyError : public Error {
 public:
  using Error::Error;
};

/// Reading or writing a mesh file failed. `file()` is the path as given; `what()` names the file
/// and the problem.
class MeshIoError : public Error {
 public:
  enum class Kind {
    Missing,            ///< the file does not exist
    Unreadable,         ///< exists but cannot be opened/parsed by the importer
    UnsupportedFormat,  ///< extension not one of .stl .obj .ply
    Empty,              ///< parsed, but holds no triangles
    NonFinite,          ///< a coordinate is NaN or infinite
    Degenerate,         ///< a triangle has (near) zero area or a repeated vertex
    NonManifold,        ///< an edge has more than two faces, a vertex is pinched, or orientation flips
    WriteFailed,        ///< the output could not be written or renamed into place
    TooLarge,           ///< holds more triangles than ImportOptions::max_faces
  };
  MeshIoError(Kind kind, std::string file, const std::string& problem)
      : Error(file + ": " + problem), kind_(kind), file_(std::move(file)) {}
  [[nodiscard]] Kind kind() const { return kind_; }
  [[nodiscard]] const std::string& file() const { return file_; }

 private:
  Kind kind_;
  std::string file_;
};

}  // namespace sutura::engine
