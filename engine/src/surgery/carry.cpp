#include "sutura/engine/surgery/carry.hpp"

#include <algorithm>

namespace sutura::engine {

namespace {

// Normalised weighted sum of quaternions, each flipped into the hemisphere of the heaviest:
// the chordal L2 mean, adequate for the nearby triads met here (neighbouring vertices or the
// copies of one vertex).
Quat mean_rotation(const std::vector<Quat>& q, const std::vector<double>& w) {
  std::size_t ref = 0;
  for (std::size_t i = 1; i < w.size(); ++i)
    if (w[i] > w[ref]) ref = i;
  Eigen::Vector4d acc = Eigen::Vector4d::Zero();
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double sign = q[i].coeffs().dot(q[ref].coeffs()) < 0 ? -1.0 : 1.0;
    acc += sign * w[i] * q[i].coeffs();
  }
  Quat out;
  out.coeffs() = acc.normalized();
  return out;
}

}  // namespace

ShellState carry_state(const EditMaps& maps, const ShellState& old) {
  ShellState s;
  s.x.resize(maps.vertices.size());
  s.D.resize(maps.vertices.size());
  std::vector<Quat> q;
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    if (o.parents.size() == 1) {
      s.x[v] = old.x[o.parents[0].index()];
      s.D[v] = old.D[o.parents[0].index()];
      continue;
    }
    Vec3 x = Vec3::Zero();
    q.clear();
    for (std::size_t i = 0; i < o.parents.size(); ++i) {
      x += o.weights[i] * old.x[o.parents[i].index()];
      q.push_back(old.D[o.parents[i].index()]);
    }
    s.x[v] = x;
    s.D[v] = mean_rotation(q, o.weights);
  }
  return s;
}

std::vector<Vec3> carry_points(const EditMaps& maps, const std::vector<Vec3>& old) {
  std::vector<Vec3> out(maps.vertices.size());
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    if (o.parents.size() == 1) {
      out[v] = old[o.parents[0].index()];
      continue;
    }
    Vec3 x = Vec3::Zero();
    for (std::size_t i = 0; i < o.parents.size(); ++i) x += o.weights[i] * old[o.parents[i].index()];
    out[v] = x;
  }
  return out;
}

RestState carry_rest(const EditMaps& maps, const RestState& old) {
  RestState r;
  r.elements.resize(maps.faces.size());
  std::vector<Quat> q(3);
  std::vector<double> w(3);
  for (std::size_t f = 0; f < maps.faces.size(); ++f) {
    const FaceOrigin& o = maps.faces[f];
    const ElementRest& p = old.elements[o.parent.index()];
    if (o.bary == Eigen::Matrix3d::Identity()) {
      r.elements[f] = p;
      continue;
    }
    ElementRest& e = r.elements[f];
    for (int k = 0; k < 3; ++k)
      e.X[k] = o.bary(k, 0) * p.X[0] + o.bary(k, 1) * p.X[1] + o.bary(k, 2) * p.X[2];
    const Eigen::Matrix3d Tp = element_frame(p.X[0], p.X[1], p.X[2]);
    const Eigen::Matrix3d Tn = element_frame(e.X[0], e.X[1], e.X[2]);
    const Quat change(Eigen::Matrix3d(Tn.transpose() * Tp));
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) {
        q[j] = p.Q[j];
        w[j] = o.bary(k, j);
      }
      e.Q[k] = (change * mean_rotation(q, w)).normalized();
    }
  }
  return r;
}

std::vector<int> carry_face_values(const EditMaps& maps, const std::vector<int>& old) {
  std::vector<int> out(maps.faces.size(), 0);
  for (std::size_t f = 0; f < maps.faces.size(); ++f)
    if (maps.faces[f].parent.index() < old.size()) out[f] = old[maps.faces[f].parent.index()];
  return out;
}

Constraints carry_constraints(const EditMaps& maps, const Constraints& old) {
  Constraints c;
  if (old.fixed.empty()) return c;
  c.fixed.assign(maps.vertices.size(), 0);
  auto mask = [&](VertexId v) -> DofMask { return v.index() < old.fixed.size() ? old.fixed[v.index()] : 0; };
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    DofMask m = mask(o.parents[0]);
    for (std::size_t i = 1; i < o.parents.size(); ++i)
      m = o.kind == VertexOriginKind::Merged ? DofMask(m | mask(o.parents[i]))
                                             : DofMask(m & mask(o.parents[i]));
    c.fixed[v] = m;
  }
  return c;
}

std::vector<FaceId> carry_face_set(const EditMaps& maps, const std::vector<FaceId>& old_faces) {
  std::vector<FaceId> sorted = old_faces;
  std::sort(sorted.begin(), sorted.end());
  std::vector<FaceId> out;
  for (std::size_t f = 0; f < maps.faces.size(); ++f)
    if (std::binary_search(sorted.begin(), sorted.end(), maps.faces[f].parent)) out.emplace_back(f);
  return out;
}

VertexId carry_vertex(const EditMaps& maps, VertexId old) {
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    if (o.kind == VertexOriginKind::Copy && o.parents.size() == 1 && o.parents[0] == old)
      return VertexId(v);
  }
  return VertexId();
}

}  // namespace sutura::engine
