#pragma once
// The GUI's camera: orbits around a target (yaw about world +z, pitch towards it), pans in
// the view plane and zooms by distance; turns a window pixel into a picking ray.
#include <array>
#include <optional>

#include "sutura/engine/geometry/bvh.hpp"
#include "sutura/render/camera.hpp"

namespace sutura::ui {

/// Standard anatomical views, named by where the eye is, in the patient frame of the bundled
/// anatomy and of `prepare` (docs/anatomy.md: +x patient's left, +y posterior, +z superior).
enum class StandardView { Anterior, Posterior, LeftLateral, RightLateral, Superior, Inferior };
inline constexpr StandardView kStandardViews[] = {StandardView::Anterior,    StandardView::Posterior,
                                                 StandardView::LeftLateral, StandardView::RightLateral,
                                                 StandardView::Superior,    StandardView::Inferior};
/// "Anterior", "Posterior", "Left lateral", "Right lateral", "Superior", "Inferior".
const char* to_string(StandardView v);

class OrbitCamera {
 public:
  /// Looks at the centre of `bounds` from the default snapshot direction, backed off so
  /// the bounding sphere fits a viewport of `aspect` (width / height).
  void fit(const std::array<render::Point3, 2>& bounds, float aspect);
  /// Rotates by a mouse drag of (dx, dy) pixels (0.3 degrees per pixel); pitch stays within
  /// +-89 degrees.
  void orbit(float dx_px, float dy_px);
  /// Moves eye and target in the view plane so the point under the cursor follows a drag of
  /// (dx, dy) pixels in a viewport `height_px` tall.
  void pan(float dx_px, float dy_px, float height_px);
  /// Looks at the same target from the same distance along the view's direction: from the
  /// front (anterior), behind, the patient's left or right with +z up, or from above or below
  /// (pitch at its +-89 degree limit; +y up on screen from above).
  void look_from(StandardView view);
  /// The standard view the camera looks from (as look_from() left it; orbiting leaves it),
  /// if any.
  [[nodiscard]] std::optional<StandardView> standard_view() const;
  /// Unit vectors (right, up on screen, forward into it) of the view, in world coordinates.
  [[nodiscard]] std::array<engine::Vec3, 3> view_axes() const;
  /// Scroll: each step towards the target shrinks the distance by 10 % (negative: away).
  void zoom(float steps);
  /// Scroll with the pointer over `p` (a point on the surface): zooms as zoom() does, moving
  /// the eye along the line to `p`, so that `p` stays under the pointer.
  void zoom_towards(const engine::Vec3& p, float steps);

  [[nodiscard]] render::Camera camera() const;
  /// Ray from the eye through pixel (x, y) of a width x height viewport, (0, 0) top-left
  /// (window coordinates); the direction has unit length.
  [[nodiscard]] engine::Ray ray_through(float x, float y, float width, float height) const;
  /// Angle (radians) one pixel subtends at the centre of a viewport `height_px` tall.
  [[nodiscard]] double radians_per_pixel(float height_px) const;
  /// Window pixel (top-left origin) where world point `p` shows; false when it is behind
  /// the eye.
  [[nodiscard]] bool project(const engine::Vec3& p, float width, float height,
                             std::array<float, 2>& pixel) const;

 private:
  [[nodiscard]] engine::Vec3 forward() const;  ///< unit, from eye to target
  engine::Vec3 target_ = engine::Vec3::Zero();
  double distance_ = 50.0;   ///< mm from target to eye
  double yaw_ = 0.0;         ///< radians about +z
  double pitch_ = 0.0;       ///< radians; positive looks down
  double fov_y_deg_ = 35.0;
};

}  // namespace sutura::ui
