#pragma once
// What the renderer draws: plain arrays only (no engine types), so the renderer never
// depends on the engine. Spans refer to caller-owned memory that must outlive the draw call.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sutura::render {

using Color = std::array<float, 3>;  ///< linear RGB in [0, 1]
using Point3 = std::array<float, 3>;

/// A shaded triangle surface. Both sides are lit (vessel walls are seen from inside too).
struct SurfaceItem {
  std::span<const float> positions;       ///< xyz per vertex
  std::span<const std::uint32_t> triangles;  ///< 3 vertex indices per triangle
  /// Optional scalar per vertex; when non-empty the surface is coloured through the scene's
  /// colour map instead of `color`.
  std::span<const float> scalars;
  Color color = {0.85f, 0.45f, 0.40f};
  bool wireframe = false;                 ///< overlay mesh edges
  Color wire_color = {0.1f, 0.1f, 0.1f};
};

/// A polyline (incision, suture chain, boundary loop), drawn on top with depth test and a
/// small depth bias so it stays visible on the surface it lies on.
struct PolylineItem {
  std::vector<Point3> points;
  Color color = {0.1f, 0.3f, 0.9f};
  float width_px = 3.0f;
  bool closed = false;
};

/// Round point markers (fixed vertices, picked points).
struct PointsItem {
  std::vector<Point3> points;
  Color color = {0.9f, 0.8f, 0.1f};
  float size_px = 8.0f;
};

enum class ColorMapName { Viridis, Coolwarm, Jet };

/// How per-vertex scalars map to colours, and the legend drawn for them.
struct ColorMap {
  ColorMapName name = ColorMapName::Viridis;
  float min = 0.0f;
  float max = 1.0f;
  std::string label;       ///< legend title, e.g. "displacement [mm]"
  bool show_legend = true;
};

struct Scene {
  std::vector<SurfaceItem> surfaces;
  std::vector<PolylineItem> polylines;
  std::vector<PointsItem> points;
  std::optional<ColorMap> color_map;  ///< used by surfaces with scalars
  Color background = {1.0f, 1.0f, 1.0f};
};

/// Axis-aligned bounds of everything in the scene; {min, max}. Empty scene: unit cube.
std::array<Point3, 2> scene_bounds(const Scene& scene);

}  // namespace sutura::render
