#include "sutura/engine/surgery/patch_plan.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/surgery/seam_match.hpp"

namespace sutura::engine {

namespace {

VertexId nearest_boundary_vertex(const SurfaceMesh& mesh, const Vec3& p) {
  VertexId best;
  double d = HUGE_VAL;
  for (const auto& loop : mesh.boundary_loops())
    for (const VertexId v : loop) {
      const double dv = (mesh.position(v) - p).squaredNorm();
      if (dv < d) d = dv, best = v;
    }
  return best;
}

double mean_edge(const SurfaceMesh& mesh, const BoundaryChain& c) {
  return chain_length(mesh, c) / double(c.vertices.size() - 1);
}

// Arc length from the chain's first vertex to each of its vertices over the whole length.
std::vector<double> arc_fractions(const SurfaceMesh& mesh, const BoundaryChain& c) {
  std::vector<double> f(c.vertices.size(), 0.0);
  for (std::size_t i = 1; i < f.size(); ++i)
    f[i] = f[i - 1] + (mesh.position(c.vertices[i]) - mesh.position(c.vertices[i - 1])).norm();
  for (double& x : f) x /= f.back();
  return f;
}

}  // namespace

PatchPlan plan_patch(const SurfaceMesh& host, const Vec3& start, const Vec3& end,
                     const PatchPlanParams& params) {
  if (!(params.width > 0)) throw InvalidArgument("patch width must be > 0");
  if (!(params.length >= 0)) throw InvalidArgument("patch length must be >= 0");
  if (!(params.edge_length >= 0)) throw InvalidArgument("patch edge_length must be >= 0");
  if (!(params.min_edge_length >= 0)) throw InvalidArgument("patch min_edge_length must be >= 0");
  PatchPlan plan;
  // The lips: the arc from start to end and the arc back (shortest candidates; for a slit they
  // are the only two arcs between the shared ends).
  ChainSpec left{start, end, std::nullopt, false, params.max_distance};
  ChainSpec right{end, start, std::nullopt, false, params.max_distance};
  plan.lip_left = find_boundary_chain(host, left);
  plan.lip_right = find_boundary_chain(host, right);
  const bool shared_start = plan.lip_left.vertices.front() == plan.lip_right.vertices.back();
  const bool shared_end = plan.lip_left.vertices.back() == plan.lip_right.vertices.front();
  if (!shared_end)
    throw InvalidArgument("the incision must end inside the surface (its two lips meeting at the "
                          "end point) for a patch");
  const bool slit = shared_start;
  if (slit && params.shape == PatchShape::Triangle)
    throw InvalidArgument("a triangular patch needs an incision opened from the boundary; use an "
                          "ellipse or a diamond for a slit");
  if (!slit && params.shape != PatchShape::Triangle)
    throw InvalidArgument("an incision opened from the boundary takes a triangular patch");

  const double len_l = chain_length(host, plan.lip_left), len_r = chain_length(host, plan.lip_right);
  plan.incision_length = 0.5 * (len_l + len_r);
  PatchParams pp;
  pp.shape = params.shape;
  pp.length = params.length > 0 ? params.length : plan.incision_length;
  pp.width = params.width;
  pp.target_edge_length =
      params.edge_length > 0
          ? params.edge_length
          : std::max(params.min_edge_length,
                     0.5 * (mean_edge(host, plan.lip_left) + mean_edge(host, plan.lip_right)));
  pp.max_faces = params.max_faces;
  // A patch is a few times as long as it is wide at most, or the other way round (a widening
  // gusset); far beyond, it is a thread or a flap no planner means, meshed ring after ring or
  // relaxed without end (a 2 mm patch on a 1e-5 mm or a 1e7 mm incision).
  constexpr double kMaxAspect = 50.0;
  if (!(pp.width <= kMaxAspect * pp.length && pp.length <= kMaxAspect * pp.width)) {
    std::ostringstream m;
    m << "a patch " << pp.width << " mm wide and " << pp.length
      << " mm long: its width and length must be within a factor of " << kMaxAspect << " of each other";
    throw InvalidArgument(m.str());
  }
  plan.rest = make_patch(pp);
  plan.edge_length = pp.target_edge_length;
  const double hl = 0.5 * pp.length, hw = 0.5 * pp.width;

  // Patch chains: from the tip at the incision's end round to the corner at its start on the
  // left side (+y), and from the start corner on the right side (-y) to the end tip.
  const Vec3 tip_end(hl, 0, 0);
  const Vec3 start_left = slit ? Vec3(-hl, 0, 0) : Vec3(-hl, hw, 0);
  const Vec3 start_right = slit ? Vec3(-hl, 0, 0) : Vec3(-hl, -hw, 0);
  const VertexId e = nearest_boundary_vertex(plan.rest, tip_end);
  plan.edge_left = boundary_chain(plan.rest, e, nearest_boundary_vertex(plan.rest, start_left));
  plan.edge_right = boundary_chain(plan.rest, nearest_boundary_vertex(plan.rest, start_right), e);
  if (params.left_segments > 0 || params.right_segments > 0) {
    if (params.left_segments < 1 || params.right_segments < 1)
      throw InvalidArgument("patch: left_segments and right_segments must both be >= 1");
    // Flat and unstressed, the patch is remeshed in its rest shape: exact.
    ResampleChainsParams rp;
    rp.target_edge_length = pp.target_edge_length;
    rp.band_passes = params.seam_passes;
    const ResampleChainsResult r = resample_chains(
        plan.rest,
        {{plan.edge_left, equal_fractions(params.left_segments)},
         {plan.edge_right, equal_fractions(params.right_segments)}},
        rp);
    plan.rest = r.mesh;
    plan.edge_left = r.chains[0];
    plan.edge_right = r.chains[1];
  }

  // Initial placement: a tent over the closed slit. Along the cut the patch follows the lips;
  // across it it is compressed to a narrow band (lateral scale k) and arched outwards, so that
  // (a) its edges start next to the lips they are sutured to, and the lips, which meet the
  // patch edges at their mean, move by at most a fifth of their edge length (no host triangle
  // is folded), and (b) the map from the flat patch is an immersion (no patch triangle is
  // degenerate, even at the tips where both edges meet). y0 is congruent with this shape; the
  // relaxation then opens the slit to the patch's true width.
  const auto vn = host.vertex_normals();
  const auto& lip = plan.lip_left.vertices;
  std::vector<double> arc(lip.size(), 0.0);
  for (std::size_t i = 1; i < lip.size(); ++i)
    arc[i] = arc[i - 1] + (host.position(lip[i]) - host.position(lip[i - 1])).norm();
  auto lip_at = [&](double fraction, Vec3& point, Vec3& tangent, Vec3& normal) {
    const double target = std::clamp(fraction, 0.0, 1.0) * arc.back();
    std::size_t i = 0;
    while (i + 2 < lip.size() && arc[i + 1] < target) ++i;
    const double t = std::clamp((target - arc[i]) / std::max(arc[i + 1] - arc[i], 1e-300), 0.0, 1.0);
    const Vec3 p0 = host.position(lip[i]), p1 = host.position(lip[i + 1]);
    point = (1 - t) * p0 + t * p1;
    tangent = (p1 - p0).normalized();
    normal = ((1 - t) * vn[lip[i].index()] + t * vn[lip[i + 1].index()]).normalized();
  };
  auto half_width = [&](double px) {  // of the outline at px
    const double u = std::clamp(px / hl, -1.0, 1.0);
    switch (pp.shape) {
      case PatchShape::Ellipse: return hw * std::sqrt(std::max(0.0, 1.0 - u * u));
      case PatchShape::Diamond: return hw * (1.0 - std::abs(u));
      case PatchShape::Triangle: return hw * 0.5 * (1.0 - u);
    }
    return hw;
  };
  const double lip_edge = 0.5 * (mean_edge(host, plan.lip_left) + mean_edge(host, plan.lip_right));
  const double k = std::min(1.0, 0.4 * lip_edge / hw);
  // Where along the lips a flat point goes: its x over the length, or, for matched seams
  // (one edge vertex per lip vertex, paired in order), the lip fraction of each edge vertex's
  // partner, interpolated in x along each edge and blended across the patch, so that every
  // edge vertex lands beside its own lip vertex. Both are increasing in x: an immersion.
  std::vector<std::pair<double, double>> table_left, table_right;  // (x, lip fraction)
  const auto& rest_x = plan.rest.positions();
  const std::size_t nl = plan.lip_left.vertices.size(), nr = plan.lip_right.vertices.size();
  const bool matched = params.left_segments > 0 && plan.edge_left.vertices.size() == nl &&
                       plan.edge_right.vertices.size() == nr;
  if (matched) {
    const std::vector<double> fl = arc_fractions(host, plan.lip_left);
    const std::vector<double> fr = arc_fractions(host, plan.lip_right);
    for (std::size_t j = 0; j < nl; ++j)  // lip_left[j] pairs with edge_left[nl - 1 - j]
      table_left.emplace_back(rest_x[plan.edge_left.vertices[nl - 1 - j].index()].x(), fl[j]);
    for (std::size_t m = 0; m < nr; ++m)  // edge_right[m] pairs with lip_right[nr - 1 - m]
      table_right.emplace_back(rest_x[plan.edge_right.vertices[m].index()].x(), 1.0 - fr[nr - 1 - m]);
  }
  auto lookup = [](const std::vector<std::pair<double, double>>& t, double x) {
    if (x <= t.front().first) return t.front().second;
    std::size_t i = 0;
    while (i + 2 < t.size() && t[i + 1].first < x) ++i;
    const double span = t[i + 1].first - t[i].first;
    const double a = span > 0.0 ? std::clamp((x - t[i].first) / span, 0.0, 1.0) : 1.0;
    return (1.0 - a) * t[i].second + a * t[i + 1].second;
  };
  std::vector<Vec3> placed;
  placed.reserve(plan.rest.num_vertices());
  for (const Vec3& p : plan.rest.positions()) {
    Vec3 point, tangent, normal;
    double u = p.x() / pp.length + 0.5;
    if (matched) {
      const double left = std::clamp(0.5 * (1.0 + p.y() / std::max(half_width(p.x()), 1e-12)), 0.0, 1.0);
      u = left * lookup(table_left, p.x()) + (1.0 - left) * lookup(table_right, p.x());
    }
    lip_at(u, point, tangent, normal);
    const Vec3 side = normal.cross(tangent).normalized();
    const double w = std::max(half_width(p.x()), 1e-12);
    const double r = std::clamp(p.y() / w, -1.0, 1.0);
    placed.push_back(point + k * p.y() * side + 0.5 * w * (1.0 - r * r) * normal);
  }
  plan.placed = SurfaceMesh(placed, plan.rest.faces());
  plan.matched = matched;

  // The rest shape is the flat patch moved rigidly onto the tangent plane at the incision's
  // middle (axes: along the cut, sideways, host normal). Rigid motions change nothing
  // intrinsic, but the nodal triads of a fresh object are the world axes: the patch's rest
  // triads must be stated in the same world as the host's, or the suture would join triads of
  // two unrelated frames (a patch cut in the z = 0 plane would want its normal along z).
  Vec3 mid_point = Vec3::Zero(), mid_normal = Vec3::Zero();
  for (const auto* chain : {&plan.lip_left, &plan.lip_right})
    for (const VertexId v : chain->vertices) {
      mid_point += host.position(v);
      mid_normal += vn[v.index()];
    }
  mid_point /= double(plan.lip_left.vertices.size() + plan.lip_right.vertices.size());
  mid_normal.normalize();
  Vec3 along = host.position(plan.lip_left.vertices.back()) - host.position(plan.lip_left.vertices.front());
  along = (along - along.dot(mid_normal) * mid_normal).normalized();
  const Vec3 across = mid_normal.cross(along);
  std::vector<Vec3> rest_world;
  rest_world.reserve(plan.rest.num_vertices());
  for (const Vec3& p : plan.rest.positions())
    rest_world.push_back(mid_point + p.x() * along + p.y() * across + p.z() * mid_normal);
  plan.rest = SurfaceMesh(std::move(rest_world), plan.rest.faces());
  return plan;
}

}  // namespace sutura::engine
