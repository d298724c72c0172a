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

/// Linear RGB in [0, 1]. Lighting is computed in linear light and images hold sRGB, so a
/// colour c shows as 255 * srgb(c): {0.5, 0.5, 0.5} becomes (188, 188, 188).
using Color = std::array<float, 3>;

/// Distinct, print-friendly surface colours, one per object in creation order (cycled): the
/// window and the saved snapshots use the same, so an object looks the same in both.
inline Color object_color(std::size_t index) {
  constexpr std::array<Color, 4> kColors = {{{0.86f, 0.42f, 0.38f},
                                             {0.40f, 0.58f, 0.85f},
                                             {0.55f, 0.75f, 0.45f},
                                             {0.85f, 0.70f, 0.35f}}};
  return kColors[index % kColors.size()];
}
using Point3 = std::array<float, 3>;

/// A shaded triangle surface. Both sides are lit (vessel walls are seen from inside too);
/// smooth shading uses area-weighted vertex normals computed from these arrays each draw.
/// The renderer throws std::invalid_argument if positions or triangles are not multiples of
/// 3, an index is out of range, or scalars are neither empty nor one per vertex.
struct SurfaceItem {
  std::span<const float> positions;       ///< xyz per vertex
  std::span<const std::uint32_t> triangles;  ///< 3 vertex indices per triangle
  /// Optional scalar per vertex; when non-empty the surface is coloured through the scene's
  /// colour map instead of `color` (Viridis over [0, 1] if the scene has none). Values are
  /// clamped to [min, max]; non-finite values show grey.
  std::span<const float> scalars;
  Color color = {0.85f, 0.45f, 0.40f};
  bool wireframe = false;                 ///< overlay mesh edges
  Color wire_color = {0.1f, 0.1f, 0.1f};
};

/// A polyline (incision, suture chain, boundary loop), drawn on top with depth test and a
/// small depth bias (1% of the scene's bounding radius, towards the eye) so it stays
/// visible on the surface it lies on. Round joints and ends. Polylines and points are
/// hidden by surfaces but not by each other: they stack in order, points last.
/// Fewer than 2 points or width_px <= 0: nothing is drawn.
struct PolylineItem {
  std::vector<Point3> points;
  Color color = {0.1f, 0.3f, 0.9f};
  float width_px = 3.0f;
  bool closed = false;
};

/// Round, anti-aliased point markers (fixed vertices, picked points), `size_px` across,
/// with the same depth bias as polylines. size_px <= 0: nothing is drawn.
struct PointsItem {
  std::vector<Point3> points;
  Color color = {0.9f, 0.8f, 0.1f};
  float size_px = 8.0f;
};

enum class ColorMapName { Viridis, Coolwarm, Jet };

/// How per-vertex scalars map to colours, and the legend drawn for them: a colour bar at
/// the right edge with max on top, min below and the label above (skipped when the image is
/// too small for it to take at most half the width).
struct ColorMap {
  ColorMapName name = ColorMapName::Viridis;
  float min = 0.0f;
  float max = 1.0f;
  /// Legend title, e.g. "displacement [mm]"; ASCII (other bytes show as '?').
  std::string label;
  bool show_legend = true;
};

/// A plane that cuts the scene open to show the inside of a vessel: what lies on the side the
/// normal points to (surfaces, wireframes, polylines and points alike) is not drawn, per pixel,
/// and the wall left is seen from both sides. The normal need not be unit length. A draw with a
/// non-finite point or normal, or a zero normal, throws std::invalid_argument. The scene's
/// bounds (and so a fitted camera) ignore the plane: cut and uncut views frame alike.
struct ClipPlane {
  Point3 point = {0.0f, 0.0f, 0.0f};
  Point3 normal = {0.0f, 0.0f, 1.0f};
};

struct Scene {
  std::vector<SurfaceItem> surfaces;
  std::vector<PolylineItem> polylines;
  std::vector<PointsItem> points;
  std::optional<ColorMap> color_map;  ///< used by surfaces with scalars
  Color background = {1.0f, 1.0f, 1.0f};
  std::optional<ClipPlane> clip;
};

/// Axis-aligned bounds of everything in the scene; {min, max}. Points with a non-finite
/// coordinate are ignored. Empty scene: the unit cube centred on the origin, [-0.5, 0.5]^3.
std::array<Point3, 2> scene_bounds(const Scene& scene);

}  // namespace sutura::render
