#include "sutura/engine/sim/selection.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

std::string describe(const Vec3& v) {
  return "(" + std::to_string(v.x()) + ", " + std::to_string(v.y()) + ", " +
         std::to_string(v.z()) + ")";
}

}  // namespace

std::vector<VertexId> select_vertices(const std::vector<Vec3>& positions, const Selection& sel) {
  std::vector<VertexId> out;
  const auto n = static_cast<std::int32_t>(positions.size());
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, SelectIds>) {
          for (VertexId v : s.ids) {
            if (v.value < 0 || v.value >= n)
              throw InvalidArgument("vertex id " + std::to_string(v.value) +
                                    " is out of range (the mesh has " + std::to_string(n) +
                                    " vertices)");
            out.push_back(v);
          }
        } else if constexpr (std::is_same_v<S, SelectNearest>) {
          if (n == 0) throw InvalidArgument("nearest-vertex selection on an empty mesh");
          for (const Vec3& q : s.points) {
            std::int32_t best = 0;
            double best_d = std::numeric_limits<double>::infinity();
            for (std::int32_t i = 0; i < n; ++i) {
              const double d = (positions[i] - q).squaredNorm();
              if (d < best_d) best_d = d, best = i;  // strict: ties keep the lowest id
            }
            out.emplace_back(best);
          }
        } else if constexpr (std::is_same_v<S, SelectBox>) {
          for (std::int32_t i = 0; i < n; ++i) {
            const Vec3& p = positions[i];
            if ((p.array() >= s.min.array()).all() && (p.array() <= s.max.array()).all())
              out.emplace_back(i);
          }
          if (out.empty())
            throw InvalidArgument("box " + describe(s.min) + " - " + describe(s.max) +
                                  " contains no vertex");
        } else {
          const double len = s.normal.norm();
          if (!(len > 0.0)) throw InvalidArgument("plane selection: normal must not be zero");
          const Vec3 nrm = s.normal / len;
          for (std::int32_t i = 0; i < n; ++i)
            if (std::abs((positions[i] - s.point).dot(nrm)) <= s.distance) out.emplace_back(i);
          if (out.empty())
            throw InvalidArgument("no vertex within " + std::to_string(s.distance) +
                                  " mm of the plane through " + describe(s.point) +
                                  " with normal " + describe(s.normal));
        }
      },
      sel);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  if (out.empty()) throw InvalidArgument("the selection matched no vertex");
  return out;
}

}  // namespace sutura::engine
