#include "sutura/app/patch_template.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "number_text.hpp"
#include "sutura/engine/surgery/flat_layout.hpp"

namespace sutura::app {

namespace {

using detail::fixed;
using engine::Vec2;

Vec2 outward(const Vec2& edge) { return Vec2(edge.y(), -edge.x()).normalized(); }

// The closed counter-clockwise polygon `p` moved `d` outwards: each edge shifted along its
// outward normal, convex corners joined by arcs (at most 10 degrees a step), reflex ones by
// the two shifted edges' intersection. Exact for convex polygons (a patch's seam is).
std::vector<Vec2> offset_outwards(const std::vector<Vec2>& p, double d) {
  if (d == 0.0) return p;
  std::vector<Vec2> out;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = p[(i + n - 1) % n];
    const Vec2& b = p[i];
    const Vec2& c = p[(i + 1) % n];
    const Vec2 n1 = outward(b - a), n2 = outward(c - b);
    // The turn from the incoming to the outgoing normal, in (-pi, pi]: > 0 at a convex corner.
    const double sweep = std::atan2(n1.x() * n2.y() - n1.y() * n2.x(), n1.dot(n2));
    if (sweep > 1e-9) {
      const double t1 = std::atan2(n1.y(), n1.x());
      const int steps = std::max(1, static_cast<int>(std::ceil(sweep / (std::numbers::pi / 18))));
      for (int j = 0; j <= steps; ++j) {
        const double t = t1 + sweep * j / steps;
        out.push_back(b + d * Vec2(std::cos(t), std::sin(t)));
      }
    } else {
      const double denominator = std::max(1.0 + n1.dot(n2), 0.25);
      out.push_back(b + d * (n1 + n2) / denominator);
    }
  }
  return out;
}

}  // namespace

std::vector<int> patch_materials(const SceneObject& obj) {
  // A material is sewn in when one of its vertices also belongs to a face of another material
  // (a suture merged them); a part added beside the object shares no vertex.
  const std::size_t nm = obj.sim.materials.size();
  std::vector<int> first(obj.mesh.num_vertices(), -1);  // the first material seen at a vertex
  std::vector<bool> used(nm, false), sewn(nm, false);
  for (std::size_t f = 0; f < obj.mesh.num_faces() && f < obj.sim.face_material.size(); ++f) {
    const int m = obj.sim.face_material[f];
    if (m < 0 || static_cast<std::size_t>(m) >= nm) continue;
    used[m] = true;
    for (engine::VertexId v : obj.mesh.face_vertices(engine::FaceId(f))) {
      int& seen = first[v.index()];
      if (seen < 0) seen = m;
      else if (seen != m) sewn[m] = sewn[seen] = true;
    }
  }
  std::vector<int> out;
  for (std::size_t m = 1; m < nm; ++m)
    if (used[m] && sewn[m]) out.push_back(static_cast<int>(m));
  return out;
}

PatchTemplate make_patch_template(const SceneObject& obj, const std::string& heading,
                                  const PatchTemplateOptions& options) {
  const std::vector<int> materials = patch_materials(obj);
  if (materials.empty())
    throw std::invalid_argument("patch: object '" + obj.name + "' has no patch (a patch op sews one in)");
  if (options.patch < 1 || options.patch > static_cast<int>(materials.size()))
    throw std::invalid_argument("patch: object '" + obj.name + "' has " +
                                std::to_string(materials.size()) + " patch" +
                                (materials.size() == 1 ? "" : "es") + "; there is no patch " +
                                std::to_string(options.patch));
  if (!(options.bite_spacing_mm >= 0.1) || !(options.bite_spacing_mm <= 20.0))
    throw std::invalid_argument("bite_spacing: must be in [0.1, 20] mm");
  if (!(options.seam_allowance_mm >= 0.0) || !(options.seam_allowance_mm <= 20.0))
    throw std::invalid_argument("seam_allowance: must be in [0, 20] mm");
  if (!options.proximal.allFinite()) throw std::invalid_argument("proximal: not a finite point");

  const int material = materials[options.patch - 1];
  std::vector<engine::FaceId> faces;
  for (std::size_t f = 0; f < obj.sim.face_material.size(); ++f)
    if (obj.sim.face_material[f] == material) faces.emplace_back(f);
  const engine::FlatLayout layout = engine::unfold_rest(obj.mesh, obj.sim.rest, faces);

  // The seam from its vertex nearest the proximal point.
  std::size_t first = 0;
  for (std::size_t i = 1; i < layout.outline.size(); ++i)
    if ((obj.mesh.position(layout.outline[i]) - options.proximal).squaredNorm() <
        (obj.mesh.position(layout.outline[first]) - options.proximal).squaredNorm())
      first = i;
  std::vector<Vec2> seam;
  for (std::size_t i = 0; i < layout.outline.size(); ++i)
    seam.push_back(layout.position[layout.outline[(first + i) % layout.outline.size()].index()]);

  // Long axis (principal direction of the seam's vertices) upright, proximal end up.
  Vec2 centre = Vec2::Zero();
  for (const Vec2& q : seam) centre += q;
  centre /= static_cast<double>(seam.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec2& q : seam) cov += (q - centre) * (q - centre).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Vec2 axis = eig.eigenvectors().col(1);
  if ((seam.front() - centre).dot(axis) < 0) axis = -axis;
  Eigen::Matrix2d R;
  R << axis.y(), -axis.x(), axis.x(), axis.y();
  for (Vec2& q : seam) q = R * (q - centre);
  const std::vector<Vec2> cut = offset_outwards(seam, options.seam_allowance_mm);

  PatchTemplate t;
  t.faces = faces.size();
  t.max_gap_mm = layout.max_gap_mm;
  t.rest_area_mm2 = layout.rest_area_mm2;
  t.rest_seam_length_mm = layout.rest_perimeter_mm;
  t.seam_length_mm = engine::polygon_perimeter(seam);
  t.area_mm2 = engine::polygon_area(seam);
  t.cut_length_mm = engine::polygon_perimeter(cut);
  Eigen::AlignedBox2d seam_box, cut_box;
  for (const Vec2& q : seam) seam_box.extend(q);
  for (const Vec2& q : cut) cut_box.extend(q);
  t.length_mm = seam_box.sizes().y();
  t.width_mm = seam_box.sizes().x();

  // The page: text at the top, the patch below it, the scale bar at the bottom.
  constexpr double kMargin = 15.0, kPatchTop = 70.0, kBelow = 40.0;
  render::VectorPage& page = t.page;
  page.width_mm = std::max(210.0, cut_box.sizes().x() + 2 * kMargin);
  page.height_mm = std::max(297.0, kPatchTop + cut_box.sizes().y() + kBelow);
  page.title = heading;
  const double x0 = 0.5 * page.width_mm - cut_box.center().x();
  const double y0 = kPatchTop + cut_box.max().y();
  auto at = [&](const Vec2& q) { return render::PagePoint{x0 + q.x(), y0 - q.y()}; };

  render::PageStroke cut_line;
  for (const Vec2& q : cut) cut_line.points.push_back(at(q));
  cut_line.closed = true;
  cut_line.width_mm = 0.35;
  page.strokes.push_back(cut_line);
  render::PageStroke seam_line;
  for (const Vec2& q : seam) seam_line.points.push_back(at(q));
  seam_line.closed = true;
  seam_line.width_mm = 0.2;
  seam_line.dash_mm = {2.0, 1.0};
  seam_line.grey = 0.35;
  page.strokes.push_back(seam_line);

  // Bite marks across the seam, from its proximal vertex on, every bite_spacing of its length.
  // A seam is at most a few hundred mm (a patch is at most 50 mm wide): bounded, but checked.
  const double bites = std::floor(t.seam_length_mm / options.bite_spacing_mm + 1e-9);
  if (!(bites <= 100000.0))
    throw std::invalid_argument("bite_spacing: " + std::to_string(bites) + " bite marks along a " +
                                fixed(t.seam_length_mm, 1) + " mm seam; give a wider spacing");
  t.bites = static_cast<int>(bites);
  std::size_t edge = 0;
  double edge_start = 0.0;
  for (int k = 0; k < t.bites; ++k) {
    const double s = k * options.bite_spacing_mm;
    while (edge + 1 < seam.size() &&
           edge_start + (seam[(edge + 1) % seam.size()] - seam[edge]).norm() <= s) {
      edge_start += (seam[edge + 1] - seam[edge]).norm();
      ++edge;
    }
    const Vec2 a = seam[edge], b = seam[(edge + 1) % seam.size()];
    const Vec2 q = a + (b - a) * std::clamp((s - edge_start) / (b - a).norm(), 0.0, 1.0);
    const Vec2 normal = outward(b - a);
    render::PageStroke tick;
    tick.points = {at(q - 0.6 * normal), at(q + 0.6 * normal)};
    tick.width_mm = 0.2;
    page.strokes.push_back(tick);
  }

  const double centre_x = 0.5 * page.width_mm;
  page.labels.push_back({{centre_x, kPatchTop - 4.0}, "PROXIMAL", 3.5, true});
  page.labels.push_back({{centre_x, kPatchTop + cut_box.sizes().y() + 6.5}, "DISTAL", 3.5, true});

  // Scale bar: 10 mm with end ticks.
  const double bar_y = page.height_mm - 20.0;
  page.strokes.push_back({{{kMargin, bar_y}, {kMargin + 10.0, bar_y}}, false, 0.3, {}, 0.0});
  page.strokes.push_back({{{kMargin, bar_y - 1.5}, {kMargin, bar_y + 1.5}}, false, 0.3, {}, 0.0});
  page.strokes.push_back({{{kMargin + 10.0, bar_y - 1.5}, {kMargin + 10.0, bar_y + 1.5}}, false, 0.3, {}, 0.0});
  page.labels.push_back({{kMargin + 13.0, bar_y + 1.2}, "10 mm: measure it after printing", 3.0, false});

  const engine::ShellMaterial& m = obj.sim.materials[material];
  const std::vector<std::string> lines = {
      heading,
      "Print at 100 % (no fit to page). Seen from the outer (adventitial) side: the lumen side faces away.",
      "Seam (dashed) " + fixed(t.seam_length_mm, 1) + " mm, area " + fixed(t.area_mm2, 1) +
          " mm2; " + fixed(t.length_mm, 1) + " mm along the axis, " + fixed(t.width_mm, 1) + " mm across.",
      "Cut (solid) " + fixed(options.seam_allowance_mm, 1) + " mm outside the seam. Bite marks every " +
          fixed(options.bite_spacing_mm, 1) + " mm (" + std::to_string(t.bites) + "), from the proximal end.",
      "Material: E " + fixed(m.youngs_modulus, 2) + " MPa, thickness " + fixed(m.thickness, 2) +
          " mm. Rest shape vs flat cut: largest gap " + fixed(t.max_gap_mm, 3) + " mm.",
  };
  for (std::size_t i = 0; i < lines.size(); ++i)
    page.labels.push_back({{kMargin, 20.0 + 7.0 * static_cast<double>(i)}, lines[i], i == 0 ? 4.0 : 3.0, false});
  return t;
}

}  // namespace sutura::app
