#include "snapshot.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "sutura/app/object_view.hpp"
#include "sutura/engine/surgery/relaxation.hpp"

namespace sutura::app {

namespace {

// The rest shape the solver sees now (y0 part-way to x0 during a relaxation), one separate
// triangle per element: split edges stay visible (paper, Fig. 2.4).
ObjectView rest_view(const SceneObject& obj, render::Color color) {
  const engine::RestState rest =
      obj.sim.relax_from ? engine::rest_at(*obj.sim.relax_from, obj.sim.rest, obj.sim.relax_s)
                         : obj.sim.rest;
  ObjectView a;
  a.name = obj.name;
  a.positions.reserve(9 * rest.elements.size());
  for (const auto& e : rest.elements)
    for (const auto& x : e.X)
      for (int k = 0; k < 3; ++k) a.positions.push_back(static_cast<float>(x[k]));
  a.plan.wall_triangles.resize(3 * rest.elements.size());
  for (std::size_t i = 0; i < a.plan.wall_triangles.size(); ++i)
    a.plan.wall_triangles[i] = static_cast<std::uint32_t>(i);
  a.color = color;  // plain: the rest shape carries no field
  return a;
}

render::Point3 to_point(const Vec3d& v) { return {float(v[0]), float(v[1]), float(v[2])}; }

std::array<render::Point3, 2> merge(const std::array<render::Point3, 2>& a,
                                    const std::array<render::Point3, 2>& b) {
  std::array<render::Point3, 2> r = a;
  for (int i = 0; i < 3; ++i) {
    r[0][i] = std::min(a[0][i], b[0][i]);
    r[1][i] = std::max(a[1][i], b[1][i]);
  }
  return r;
}

}  // namespace

render::Image SnapshotRenderer::render(const SnapshotOp& op, const Workspace& workspace) {
  std::vector<const SceneObject*> selected;
  const auto all = workspace.objects();
  if (op.objects.empty()) {
    for (const auto& o : all) selected.push_back(&o);
  } else {
    for (const auto& name : op.objects) {
      const SceneObject* o = workspace.find(name);
      if (o == nullptr)
        throw std::runtime_error("no object named '" + name + "' (objects: " +
                                 workspace.names() + ")");
      selected.push_back(o);
    }
  }
  if (selected.empty()) throw std::runtime_error("nothing to draw: the session has no objects yet");

  const ViewContent content{op.marks, op.boundaries, op.field};
  std::vector<ObjectView> after, before;
  for (std::size_t i = 0; i < selected.size(); ++i) {
    // Colour by position in the workspace so an object keeps its colour across snapshots.
    std::size_t index = 0;
    while (&all[index] != selected[i]) ++index;
    const render::Color color = render::object_color(index);
    after.push_back(object_view(*selected[i], selected[i]->mesh, color, content));
    if (op.side_by_side)
      before.push_back(op.compare_rest ? rest_view(*selected[i], color)
                                       : object_view(*selected[i], selected[i]->before, color, content));
  }

  std::optional<render::ColorMap> cmap;
  if (op.field != Field::None) {
    render::ColorMap c;
    c.label = field_label(op.field);
    if (op.range) {
      c.min = float((*op.range)[0]);
      c.max = float((*op.range)[1]);
    } else {
      // From the smallest value to the 99.5th percentile: a few needle triangles along a cut
      // (strain 0.8 where the rest of the vessel stays below 0.1) would otherwise squeeze
      // the whole repair into the bottom colour. Larger values take the top colour (the
      // renderer clamps) and the legend says so.
      std::vector<float> all;
      for (const auto* set : {&after, &before})
        for (const auto& a : *set) all.insert(all.end(), a.scalars.begin(), a.scalars.end());
      float lo = 0.0f, hi = 0.0f, top = 0.0f;
      if (!all.empty()) {
        lo = *std::min_element(all.begin(), all.end());
        top = *std::max_element(all.begin(), all.end());
        const auto k = static_cast<std::ptrdiff_t>(0.995 * double(all.size() - 1));
        std::nth_element(all.begin(), all.begin() + k, all.end());
        hi = all[static_cast<std::size_t>(k)];
      }
      // A constant field (e.g. displacement before anything moved) still needs a range.
      if (!(hi > lo)) hi = top > lo ? top : lo + 1.0f;
      if (top > hi) c.label += " (top 0.5 % clipped)";
      c.min = lo;
      c.max = hi;
    }
    if (op.field == Field::Displacement) c.name = render::ColorMapName::Viridis;
    cmap = c;
  }

  render::Scene after_scene = scene_of(after, cmap, op.wireframe);
  render::Scene before_scene = scene_of(before, cmap, op.wireframe);
  if (op.clip)
    after_scene.clip = before_scene.clip = render::ClipPlane{to_point(op.clip->point), to_point(op.clip->normal)};

  // Both views share one camera so before and after are directly comparable; each is drawn
  // left of the legend's column (only the right one draws the legend).
  const float aspect = float(op.width - render::legend_width(after_scene, op.width, op.height)) / float(op.height);
  render::Camera camera;
  if (op.camera.eye) {
    camera.eye = to_point(*op.camera.eye);
    camera.target = to_point(*op.camera.target);
    camera.up = to_point(op.camera.up);
    camera.fov_y_deg = float(op.camera.fov_deg);
  } else {
    auto bounds = render::scene_bounds(after_scene);
    if (op.side_by_side) bounds = merge(bounds, render::scene_bounds(before_scene));
    camera = render::fit_camera(bounds, aspect, to_point(op.camera.view), to_point(op.camera.up),
                                float(op.camera.fov_deg));
  }

  if (!renderer_) {
    context_ = render::create_offscreen_context();
    renderer_ = std::make_unique<render::Renderer>(*context_);
  }
  render::Image right = renderer_->render(after_scene, camera, op.width, op.height);
  if (!op.side_by_side) return right;
  render::RenderOptions left_options;
  left_options.draw_legend = false;  // one legend, on the right, serves both views
  left_options.legend_space = true;
  render::Image left = renderer_->render(before_scene, camera, op.width, op.height, left_options);
  return op.compare_rest ? render::side_by_side(left, right, "Rest shape", "Shape")
                         : render::side_by_side(left, right, "Before", "After");
}

}  // namespace sutura::app
