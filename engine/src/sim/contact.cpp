#include "sutura/engine/sim/contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include <Eigen/Eigenvalues>

#include "sutura/engine/errors.hpp"

namespace sutura::engine {

namespace {

// Uniform grid broad phase. Every triangle is entered into each cell its bounding box,
// inflated by the activation distance, overlaps; a vertex then only needs the triangles
// listed in its own cell. Entries are sorted by (cell, triangle), so candidates come out in
// triangle order.
class TriangleGrid {
 public:
  TriangleGrid(const std::vector<Eigen::AlignedBox3d>& boxes, const Eigen::AlignedBox3d& domain,
               double min_cell) {
    double mean_extent = 0.0;
    for (const auto& b : boxes) mean_extent += b.sizes().maxCoeff();
    mean_extent /= static_cast<double>(std::max<std::size_t>(boxes.size(), 1));
    // Cells about one (inflated) triangle wide; at most 2^20 per axis so keys fit 21 bits.
    cell_ = std::max({min_cell, mean_extent, domain.sizes().maxCoeff() / double(1 << 20)});
    origin_ = domain.min();
    for (std::size_t t = 0; t < boxes.size(); ++t) {
      const auto lo = coords(boxes[t].min()), hi = coords(boxes[t].max());
      for (std::uint64_t z = lo[2]; z <= hi[2]; ++z)
        for (std::uint64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::uint64_t x = lo[0]; x <= hi[0]; ++x)
            entries_.emplace_back(key({x, y, z}), static_cast<std::int32_t>(t));
    }
    std::sort(entries_.begin(), entries_.end());
  }

  /// Triangles listed in the cell of p, ascending.
  template <class F>
  void for_each_candidate(const Vec3& p, F&& f) const {
    const std::uint64_t k = key(coords(p));
    auto it = std::lower_bound(entries_.begin(), entries_.end(), std::make_pair(k, std::int32_t{0}));
    for (; it != entries_.end() && it->first == k; ++it) f(it->second);
  }

 private:
  [[nodiscard]] std::array<std::uint64_t, 3> coords(const Vec3& p) const {
    std::array<std::uint64_t, 3> c{};
    for (int i = 0; i < 3; ++i)
      c[i] = static_cast<std::uint64_t>(
          std::clamp(std::floor((p[i] - origin_[i]) / cell_), 0.0, double((1 << 21) - 1)));
    return c;
  }
  static std::uint64_t key(const std::array<std::uint64_t, 3>& c) {
    return c[0] | (c[1] << 21) | (c[2] << 42);
  }

  Vec3 origin_;
  double cell_ = 1.0;
  std::vector<std::pair<std::uint64_t, std::int32_t>> entries_;
};

// Energy A psi(d) of one pair with its gradient and Hessian over (p, t0, t1, t2), as functions
// of b = d^2: with phi(b) = psi(sqrt b),
//   phi'(b)  = psi'(d) / (2 d),   phi''(b) = (psi''(d) d - psi'(d)) / (4 d^3),
//   grad E = A phi' grad b,       hess E = A (phi'' grad b grad b^T + phi' hess b).
struct PairEnergy {
  double energy = 0.0;
  Vec12 gradient = Vec12::Zero();
  Mat12 hessian = Mat12::Zero();
};

PairEnergy pair_energy(const ContactParams& prm, double area, const Vec3& p, const Vec3& t0,
                       const Vec3& t1, const Vec3& t2, bool with_hessian) {
  PairEnergy out;
  const PointTriangleDistance dist = point_triangle_squared_distance(p, t0, t1, t2, with_hessian);
  const double b = dist.closest.squared_distance;
  const double dh = prm.distance, k = prm.stiffness;
  const double d = std::sqrt(b);
  if (!(d < dh)) return out;
  const double gap = dh - d;
  out.energy = area * k / (3.0 * dh) * gap * gap * gap;
  // At d = 0 the direction of the force is undefined (the distance has a cone there): the
  // pair keeps its energy but exerts nothing.
  if (d == 0.0) return out;
  const double psi1 = -k / dh * gap * gap, psi2 = 2.0 * k / dh * gap;
  const double phi1 = psi1 / (2.0 * d);
  out.gradient = area * phi1 * dist.gradient;
  if (!with_hessian) return out;
  const double phi2 = (psi2 * d - psi1) / (4.0 * d * d * d);
  out.hessian = area * (phi2 * dist.gradient * dist.gradient.transpose() + phi1 * dist.hessian);
  if (prm.project_hessian) {
    const Eigen::SelfAdjointEigenSolver<Mat12> eig(out.hessian);
    out.hessian = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() *
                  eig.eigenvectors().transpose();
  }
  return out;
}

}  // namespace

void validate(const ContactParams& p) {
  if (!(p.distance > 0.0) || !std::isfinite(p.distance))
    throw InvalidArgument("contact: distance must be a positive finite number of mm (got " +
                          std::to_string(p.distance) + ")");
  if (!(p.stiffness > 0.0) || !std::isfinite(p.stiffness))
    throw InvalidArgument("contact: stiffness must be a positive finite number of N/mm^3 (got " +
                          std::to_string(p.stiffness) + ")");
}

ContactTerm::ContactTerm(const ShellProblem& problem, const std::vector<ContactSurface>& surfaces,
                         const ContactParams& params)
    : params_(params) {
  validate(params);
  if (surfaces.size() < 2) throw InvalidArgument("contact: needs at least two surfaces");
  if (problem.faces == nullptr || problem.rest == nullptr ||
      problem.rest->elements.size() != problem.faces->size())
    throw InvalidArgument("contact: the problem needs faces and one rest element per face");
  const auto& faces = *problem.faces;
  std::vector<std::int32_t> owner(problem.num_nodes, -1);
  std::vector<double> area(problem.num_nodes, 0.0);
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    if (surfaces[s].faces.empty())
      throw InvalidArgument("contact: surface " + std::to_string(s) + " has no faces");
    for (FaceId f : surfaces[s].faces) {
      if (!f.valid() || f.index() >= faces.size())
        throw InvalidArgument("contact: surface " + std::to_string(s) + " names face " +
                              std::to_string(f.value) + " of " + std::to_string(faces.size()));
      const double a = rest_area(problem.rest->elements[f.index()]);
      for (std::int32_t n : faces[f.index()]) {
        if (n < 0 || static_cast<std::size_t>(n) >= problem.num_nodes)
          throw InvalidArgument("contact: face " + std::to_string(f.value) + " uses node " +
                                std::to_string(n) + " of " + std::to_string(problem.num_nodes));
        std::int32_t& o = owner[static_cast<std::size_t>(n)];
        if (o >= 0 && o != static_cast<std::int32_t>(s))
          throw InvalidArgument("contact: node " + std::to_string(n) + " belongs to surfaces " +
                                std::to_string(o) + " and " + std::to_string(s));
        o = static_cast<std::int32_t>(s);
        area[static_cast<std::size_t>(n)] += a / 3.0;
        max_node_ = std::max(max_node_, n);
      }
      triangles_.push_back({faces[f.index()], static_cast<std::int32_t>(s), f});
    }
  }
  for (std::size_t s = 0; s < surfaces.size(); ++s)
    for (std::size_t n = 0; n < owner.size(); ++n)
      if (owner[n] == static_cast<std::int32_t>(s))
        vertices_.push_back({static_cast<std::int32_t>(n), owner[n], area[n]});
}

std::vector<std::vector<ContactTerm::Hit>> ContactTerm::search(const ShellState& s) const {
  if (s.x.size() <= static_cast<std::size_t>(max_node_))
    throw InvalidArgument("contact: the state has " + std::to_string(s.x.size()) +
                          " positions but the surfaces use node " + std::to_string(max_node_));
  const double dh = params_.distance;
  std::vector<Eigen::AlignedBox3d> boxes(triangles_.size());
  Eigen::AlignedBox3d domain;
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    for (std::int32_t n : triangles_[t].nodes) boxes[t].extend(s.x[static_cast<std::size_t>(n)]);
    boxes[t].min().array() -= dh;
    boxes[t].max().array() += dh;
    domain.extend(boxes[t]);
  }
  for (const Vertex& v : vertices_) domain.extend(s.x[static_cast<std::size_t>(v.node)]);
  const TriangleGrid grid(boxes, domain, 2.0 * dh);

  std::vector<std::vector<Hit>> hits(vertices_.size());
  const auto nv = static_cast<std::int64_t>(vertices_.size());
#pragma omp parallel for schedule(dynamic, 256) if (nv >= 2048)
  for (std::int64_t i = 0; i < nv; ++i) {
    const Vertex& v = vertices_[static_cast<std::size_t>(i)];
    const Vec3& p = s.x[static_cast<std::size_t>(v.node)];
    grid.for_each_candidate(p, [&](std::int32_t t) {
      const Triangle& tri = triangles_[static_cast<std::size_t>(t)];
      if (tri.surface == v.surface || !boxes[static_cast<std::size_t>(t)].contains(p)) return;
      const auto& x = s.x;
      const PointTriangleClosest c = closest_point_on_triangle(
          p, x[static_cast<std::size_t>(tri.nodes[0])], x[static_cast<std::size_t>(tri.nodes[1])],
          x[static_cast<std::size_t>(tri.nodes[2])]);
      if (c.squared_distance < dh * dh) hits[static_cast<std::size_t>(i)].push_back({t, c});
    });
  }
  return hits;
}

double ContactTerm::add_energy_gradient_hessian(const ShellState& s, int dofs_per_node,
                                                Eigen::VectorXd& g, Triplets* K) const {
  const std::vector<std::vector<Hit>> hits = search(s);
  const bool with_hessian = K != nullptr;
  // Pair contributions in parallel into per-vertex slots, summed below in a fixed order.
  std::vector<std::vector<PairEnergy>> slots(vertices_.size());
  const auto nv = static_cast<std::int64_t>(vertices_.size());
#pragma omp parallel for schedule(dynamic, 256) if (nv >= 2048)
  for (std::int64_t i = 0; i < nv; ++i) {
    const auto& vh = hits[static_cast<std::size_t>(i)];
    if (vh.empty()) continue;
    const Vertex& v = vertices_[static_cast<std::size_t>(i)];
    auto& out = slots[static_cast<std::size_t>(i)];
    out.reserve(vh.size());
    for (const Hit& h : vh) {
      const auto& n = triangles_[static_cast<std::size_t>(h.triangle)].nodes;
      const auto& x = s.x;
      out.push_back(pair_energy(params_, v.area, x[static_cast<std::size_t>(v.node)],
                                x[static_cast<std::size_t>(n[0])], x[static_cast<std::size_t>(n[1])],
                                x[static_cast<std::size_t>(n[2])], with_hessian));
    }
  }
  double energy = 0.0;
  const auto d = static_cast<Eigen::Index>(dofs_per_node);
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    for (std::size_t j = 0; j < slots[i].size(); ++j) {
      const PairEnergy& pe = slots[i][j];
      const auto& tn = triangles_[static_cast<std::size_t>(hits[i][j].triangle)].nodes;
      const std::array<Eigen::Index, 4> nodes = {vertices_[i].node, tn[0], tn[1], tn[2]};
      energy += pe.energy;
      for (int a = 0; a < 4; ++a) g.segment<3>(nodes[a] * d) += pe.gradient.segment<3>(3 * a);
      if (!with_hessian) continue;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
              K->emplace_back(nodes[a] * d + r, nodes[b] * d + c, pe.hessian(3 * a + r, 3 * b + c));
    }
  }
  return energy;
}

std::vector<ContactPair> ContactTerm::pairs(const ShellState& s) const {
  const std::vector<std::vector<Hit>> hits = search(s);
  std::vector<ContactPair> out;
  for (std::size_t i = 0; i < hits.size(); ++i)
    for (const Hit& h : hits[i])
      out.push_back({static_cast<std::size_t>(vertices_[i].node),
                     triangles_[static_cast<std::size_t>(h.triangle)].face, h.closest.feature,
                     std::sqrt(h.closest.squared_distance)});
  return out;
}

}  // namespace sutura::engine
