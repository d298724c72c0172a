#include "sutura/engine/sim/loads.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "../shell/so3.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

using so3::skew;

bool Loads::empty() const {
  return nodal.empty() && pressures.empty() && body_force_per_area.isZero();
}

bool Loads::has_moments() const {
  for (const auto& l : nodal)
    if (!l.moment.isZero()) return true;
  return false;
}

std::vector<NodalLoad> lump_line_load(const std::vector<Vec3>& positions,
                                      const std::vector<VertexId>& chain,
                                      const Vec3& force_per_length) {
  if (chain.size() < 2) throw InvalidArgument("a line load needs a chain of at least 2 vertices");
  std::vector<NodalLoad> out(chain.size());
  for (std::size_t i = 0; i < chain.size(); ++i) out[i].node = chain[i].index();
  for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
    const double len = (positions[chain[i + 1].index()] - positions[chain[i].index()]).norm();
    out[i].force += 0.5 * len * force_per_length;
    out[i + 1].force += 0.5 * len * force_per_length;
  }
  return out;
}

void external_forces(const ShellProblem& p, const ShellState& s, const Loads& loads, double lambda,
                     int d, Eigen::VectorXd& f, Triplets* K) {
  f.setZero(static_cast<Eigen::Index>(p.num_nodes * d));
  for (const auto& l : loads.nodal) {
    if (l.node >= p.num_nodes)
      throw InvalidArgument("load on node " + std::to_string(l.node) + " out of range");
    f.segment<3>(l.node * d) += lambda * l.force;
    if (!l.moment.isZero()) {
      if (d < 6) throw InvalidArgument("moments need a shell model with rotational degrees of freedom");
      f.segment<3>(l.node * d + 3) += lambda * l.moment;
    }
  }
  const auto& faces = *p.faces;
  if (!loads.body_force_per_area.isZero()) {
    for (std::size_t e = 0; e < faces.size(); ++e) {
      const Vec3 share = lambda * rest_area(p.rest->elements[e]) / 3.0 * loads.body_force_per_area;
      for (int k = 0; k < 3; ++k) f.segment<3>(faces[e][k] * d) += share;
    }
  }
  for (const auto& pl : loads.pressures) {
    const std::size_t count = pl.faces.empty() ? faces.size() : pl.faces.size();
    const double c = lambda * pl.pressure / 6.0;  // p*A*n/3 = p/6 * (e1 x e2) per corner
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t e = pl.faces.empty() ? i : pl.faces[i].index();
      const auto& fc = faces[e];
      const Vec3 e1 = s.x[fc[1]] - s.x[fc[0]], e2 = s.x[fc[2]] - s.x[fc[0]];
      const Vec3 share = c * e1.cross(e2);
      for (int k = 0; k < 3; ++k) f.segment<3>(fc[k] * d) += share;
      if (K == nullptr) continue;
      // d(share)/d(x_corner): corner 0: c([e2]x - [e1]x), corner 1: -c[e2]x, corner 2: c[e1]x.
      // The tangent gets MINUS this (follower load stiffness), symmetrised: 0.5 (A + A^T) per
      // block pair, i.e. each non-symmetric block contributes half to (a,b) and half to (b,a).
      const Eigen::Matrix3d dS[3] = {c * (skew(e2) - skew(e1)), -c * skew(e2), c * skew(e1)};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const Eigen::Matrix3d& blk = dS[b];  // d f_a / d x_b (same share on every corner a)
          for (int i2 = 0; i2 < 3; ++i2)
            for (int j2 = 0; j2 < 3; ++j2) {
              const double v = -0.5 * blk(i2, j2);
              K->emplace_back(fc[a] * d + i2, fc[b] * d + j2, v);
              K->emplace_back(fc[b] * d + j2, fc[a] * d + i2, v);
            }
        }
    }
  }
}

double load_work(const ShellProblem& p, const ShellState& from, const ShellState& to,
                 const Loads& loads, double lambda) {
  if (from.x.size() != p.num_nodes || to.x.size() != p.num_nodes)
    throw InvalidArgument("load_work: the states do not match the problem's node count");
  double work = 0.0;
  for (const auto& l : loads.nodal) {
    if (l.node >= p.num_nodes)
      throw InvalidArgument("load on node " + std::to_string(l.node) + " out of range");
    work += l.force.dot(to.x[l.node] - from.x[l.node]);
    if (!l.moment.isZero()) {
      const Eigen::AngleAxisd turn(to.D[l.node] * from.D[l.node].inverse());
      work += l.moment.dot(turn.angle() * turn.axis());
    }
  }
  const auto& faces = *p.faces;
  if (!loads.body_force_per_area.isZero()) {
    for (std::size_t e = 0; e < faces.size(); ++e) {
      const Vec3 share = rest_area(p.rest->elements[e]) / 3.0 * loads.body_force_per_area;
      for (int k = 0; k < 3; ++k) work += share.dot(to.x[faces[e][k]] - from.x[faces[e][k]]);
    }
  }
  for (const auto& pl : loads.pressures) {
    const std::size_t count = pl.faces.empty() ? faces.size() : pl.faces.size();
    // The volume change face by face (a difference of two signed tetrahedron volumes against
    // the origin); summing the differences keeps the round-off of two large volumes out.
    double dv = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      const auto& fc = faces[pl.faces.empty() ? i : pl.faces[i].index()];
      dv += to.x[fc[0]].dot(to.x[fc[1]].cross(to.x[fc[2]])) -
            from.x[fc[0]].dot(from.x[fc[1]].cross(from.x[fc[2]]));
    }
    work += pl.pressure * dv / 6.0;
  }
  return lambda * work;
}

std::vector<std::size_t> free_pressure_rim(const ShellProblem& p, const Loads& loads,
                                           const Constraints& constraints) {
  const auto& faces = *p.faces;
  // Net pressure across each edge: every pressurised face adds its pressure with the sign of
  // the direction in which it runs along the edge; with the same pressure on both sides of a
  // consistently oriented edge the two cancel exactly.
  struct Side {
    std::uint64_t edge;  // lower vertex << 32 | higher vertex
    double pressure;     // signed by the face's direction along the edge
  };
  std::vector<Side> sides;
  double largest = 0.0;
  for (const auto& pl : loads.pressures) {
    if (pl.pressure == 0.0) continue;
    largest = std::max(largest, std::abs(pl.pressure));
    const std::size_t count = pl.faces.empty() ? faces.size() : pl.faces.size();
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t e = pl.faces.empty() ? i : pl.faces[i].index();
      if (e >= faces.size())
        throw InvalidArgument("pressure on face " + std::to_string(e) + " out of range");
      const auto& fc = faces[e];
      for (int k = 0; k < 3; ++k) {
        const auto a = static_cast<std::uint64_t>(fc[k]), b = static_cast<std::uint64_t>(fc[(k + 1) % 3]);
        sides.push_back(a < b ? Side{a << 32 | b, pl.pressure} : Side{b << 32 | a, -pl.pressure});
      }
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& l, const Side& r) {
    return l.edge != r.edge ? l.edge < r.edge : l.pressure < r.pressure;
  });
  const auto held = [&](std::size_t v) {
    return constraints.is_fixed(v, 0) && constraints.is_fixed(v, 1) && constraints.is_fixed(v, 2);
  };
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    double net = 0.0;
    for (; j < sides.size() && sides[j].edge == sides[i].edge; ++j) net += sides[j].pressure;
    // Several pressure loads may cover one face (summed in another order on each side).
    if (std::abs(net) > 1e-12 * largest) {
      for (const std::size_t v : {static_cast<std::size_t>(sides[i].edge >> 32),
                                  static_cast<std::size_t>(sides[i].edge & 0xffffffffu)})
        if (!held(v)) out.push_back(v);
    }
    i = j;
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace sutura::engine
