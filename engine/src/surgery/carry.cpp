#include "sutura/engine/surgery/carry.hpp"

#include <algorithm>

#include "sutura/engine/errors.hpp"

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

namespace {

// Rest of a Resampled face by strain transfer (carry.hpp).
ElementRest resampled_rest(const FaceOrigin& o, const ElementRest& p, const FaceIndices& new_face,
                           const EditGeometry& g) {
  const FaceIndices& pf = g.old_faces[o.parent.index()];
  const Vec3 x0 = g.old_state.x[pf[0]], x1 = g.old_state.x[pf[1]], x2 = g.old_state.x[pf[2]];
  const Eigen::Matrix3d Tc = element_frame(x0, x1, x2);
  const Eigen::Matrix3d Tr = element_frame(p.X[0], p.X[1], p.X[2]);
  // In-plane map of the parent, current -> rest, in its two local frames.
  Eigen::Matrix2d a, A;
  a.col(0) = (Tc.transpose() * (x1 - x0)).head<2>();
  a.col(1) = (Tc.transpose() * (x2 - x0)).head<2>();
  A.col(0) = (Tr.transpose() * (p.X[1] - p.X[0])).head<2>();
  A.col(1) = (Tr.transpose() * (p.X[2] - p.X[0])).head<2>();
  Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
  G.topLeftCorner<2, 2>() = A * a.inverse();
  // The new triangle, turned into the parent's plane, in the parent's current frame.
  const Vec3 y0 = g.new_state.x[new_face[0]], y1 = g.new_state.x[new_face[1]],
             y2 = g.new_state.x[new_face[2]];
  const Eigen::Matrix3d Te = element_frame(y0, y1, y2);
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(Te.col(2), Tc.col(2)).toRotationMatrix();
  const Eigen::Matrix3d M = Tc.transpose() * R;  // world (new face) -> parent-current coordinates
  ElementRest e;
  e.X[0] = Vec3::Zero();
  e.X[1] = G * (M * (y1 - y0));
  e.X[2] = G * (M * (y2 - y0));
  const Eigen::Matrix3d U = element_frame(e.X[0], e.X[1], e.X[2]);
  // Triad deviation of the parent at each corner, rest-frame <- current-frame.
  std::vector<Quat> dev(3);
  for (int j = 0; j < 3; ++j)
    dev[j] = (p.Q[j] * Quat(Eigen::Matrix3d(Tc.transpose() * g.old_state.D[pf[j]].toRotationMatrix()))
                           .conjugate())
                 .normalized();
  std::vector<double> w(3);
  for (int k = 0; k < 3; ++k) {
    double sum = 0.0;
    for (int j = 0; j < 3; ++j) sum += (w[j] = std::max(0.0, o.bary(k, j)));
    if (!(sum > 0.0)) w = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    else
      for (double& wj : w) wj /= sum;
    const Quat d = mean_rotation(dev, w);
    const Eigen::Matrix3d q =
        U.transpose() * d.toRotationMatrix() * M * g.new_state.D[new_face[k]].toRotationMatrix();
    e.Q[k] = Quat(q).normalized();
  }
  return e;
}

}  // namespace

RestState carry_rest(const EditMaps& maps, const RestState& old, const EditGeometry* geometry) {
  RestState r;
  r.elements.resize(maps.faces.size());
  std::vector<Quat> q(3);
  std::vector<double> w(3);
  for (std::size_t f = 0; f < maps.faces.size(); ++f) {
    const FaceOrigin& o = maps.faces[f];
    const ElementRest& p = old.elements[o.parent.index()];
    if (o.kind == FaceOriginKind::Resampled) {
      if (geometry == nullptr)
        throw InvalidArgument("carry_rest: a resampled face needs the edit's geometry");
      r.elements[f] = resampled_rest(o, p, geometry->new_faces[f], *geometry);
      continue;
    }
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
