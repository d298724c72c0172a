#include "sutura/engine/measure/lumen_profile.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// Arc-length parametrised polyline.
class Polyline {
 public:
  explicit Polyline(const std::vector<Vec3>& points) : points_(points), s_(points.size(), 0.0) {
    for (std::size_t i = 1; i < points.size(); ++i) s_[i] = s_[i - 1] + (points[i] - points[i - 1]).norm();
  }
  [[nodiscard]] double length() const { return s_.back(); }
  [[nodiscard]] Vec3 at(double s) const {
    s = std::clamp(s, 0.0, length());
    const auto it = std::upper_bound(s_.begin() + 1, s_.end() - 1, s);
    const std::size_t i = static_cast<std::size_t>(it - s_.begin()) - 1;
    const double t = (s - s_[i]) / (s_[i + 1] - s_[i]);
    return points_[i] + t * (points_[i + 1] - points_[i]);
  }

 private:
  const std::vector<Vec3>& points_;
  std::vector<double> s_;
};

}  // namespace

LumenProfile lumen_profile(const SurfaceMesh& mesh, const std::vector<Vec3>& centreline,
                           const LumenProfileParams& params) {
  if (params.stations < 1) throw InvalidArgument("lumen_profile: stations must be at least 1");
  if (centreline.size() < 2)
    throw InvalidArgument("lumen_profile: the centreline needs at least two points");
  for (std::size_t i = 0; i < centreline.size(); ++i) {
    if (!centreline[i].allFinite())
      throw InvalidArgument("lumen_profile: centreline point " + std::to_string(i) + " is not finite");
    if (i > 0 && centreline[i] == centreline[i - 1])
      throw InvalidArgument("lumen_profile: centreline point " + std::to_string(i) +
                            " repeats the previous one");
  }
  const Polyline line(centreline);
  const double spacing = line.length() / params.stations;
  CrossSectionParams cs;
  cs.max_radius = params.max_radius;

  LumenProfile out;
  double min_area = 0.0;
  for (int k = 0; k < params.stations; ++k) {
    LumenStation st;
    st.arc_length = (k + 0.5) * spacing;
    st.plane.origin = line.at(st.arc_length);
    const Vec3 tangent =
        line.at(st.arc_length + 0.5 * spacing) - line.at(st.arc_length - 0.5 * spacing);
    if (!(tangent.norm() > 0.0))
      throw InvalidArgument("lumen_profile: the centreline folds back onto itself at arc length " +
                            std::to_string(st.arc_length));
    st.plane.normal = tangent.normalized();
    try {
      st.section = cross_section(mesh, st.plane, cs);
    } catch (const InvalidArgument&) {
      // The only failure left after the checks above: the plane misses the surface.
      st.section.reset();
    }
    if (st.section && st.section->closed && (!out.min_area_station || st.section->area < min_area)) {
      out.min_area_station = out.stations.size();
      min_area = st.section->area;
    }
    out.stations.push_back(std::move(st));
  }
  return out;
}

}  // namespace sutura::engine
