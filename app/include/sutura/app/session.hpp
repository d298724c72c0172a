#pragma once
// Planning sessions: a JSON Lines file, one action per line, after a versioned header line.
// The format is documented in docs/session-format.md; this header is its parser.
//
// Every field is checked while parsing, before anything runs, so a typo on line 40 is
// reported before a minute of simulation is spent on lines 1-39. Unknown fields are errors
// too (a misspelt optional field would otherwise be silently ignored).
#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "sutura/engine/generators.hpp"

namespace sutura::app {

/// The newest session format version this build reads and writes.
inline constexpr int kSessionFormatVersion = 1;

/// A session that cannot be read or run. `what()` reads "FILE:LINE: op 'OP': field 'F': problem"
/// with the parts that are known.
class SessionError : public std::runtime_error {
 public:
  SessionError(std::string file, int line, std::string op, std::string field,
               const std::string& problem);
  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] int line() const { return line_; }  ///< 1-based; 0 when not tied to a line
  [[nodiscard]] const std::string& op() const { return op_; }
  [[nodiscard]] const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_;
  std::string op_;
  std::string field_;
};

using Vec3f = std::array<double, 3>;

// --- ops ----------------------------------------------------------------------------------

/// Creates an object from a procedural generator.
struct GenerateOp {
  std::string object;
  std::variant<engine::TubeParams, engine::StripParams, engine::PatchParams> params;
  Vec3f translate = {0, 0, 0};  ///< mm, applied after generation
};

/// Loads an object from a mesh file (path relative to the session file).
struct LoadOp {
  std::string object;
  std::filesystem::path file;  ///< resolved against the session file's directory
  double weld_tolerance = 1e-6;
};

/// Camera of a snapshot: explicit eye/target/up, or a view direction fitted to the objects.
struct CameraSpec {
  std::optional<Vec3f> eye;     ///< with target: explicit camera
  std::optional<Vec3f> target;
  Vec3f up = {0, 0, 1};
  Vec3f view = {-0.4, 1.0, -0.35};  ///< direction from the eye towards the scene when fitted
  double fov_deg = 35.0;
};

/// Per-vertex field shown as colours.
enum class Field { None, Displacement, X, Y, Z };

/// Renders the named objects (all when empty) to a PNG inside the output directory.
struct SnapshotOp {
  std::filesystem::path file;  ///< relative to the output directory
  int width = 1600;
  int height = 900;  ///< pixels of each view
  std::vector<std::string> objects;
  Field field = Field::None;
  std::optional<std::array<double, 2>> range;  ///< colour-map range; default: data min/max
  CameraSpec camera;
  bool side_by_side = false;  ///< before | after, each width x height
  bool wireframe = false;
  bool boundaries = true;     ///< draw boundary loops as polylines
};

/// Writes an object's current mesh (.obj/.ply/.stl) inside the output directory.
struct ExportOp {
  std::string object;
  std::filesystem::path file;
};

/// Writes the report so far (JSON) inside the output directory.
struct ReportOp {
  std::filesystem::path file;
};

using Op = std::variant<GenerateOp, LoadOp, SnapshotOp, ExportOp, ReportOp>;

/// One parsed action with where it came from.
struct Action {
  int line = 0;     ///< 1-based line in the session file
  std::string name; ///< the op name as written ("generate", ...)
  Op op;
};

struct Session {
  std::filesystem::path file;  ///< the session file (for messages and relative inputs)
  int version = kSessionFormatVersion;
  std::string description;
  std::vector<Action> actions;
};

/// Reads and checks a session file. Throws SessionError naming file, line and field.
Session load_session(const std::filesystem::path& file);

/// Parses session text; `file` is used for messages and to resolve relative input paths.
Session parse_session(const std::string& text, const std::filesystem::path& file);

/// Names of every op this build understands (for messages and docs tests).
const std::vector<std::string>& known_ops();

}  // namespace sutura::app
