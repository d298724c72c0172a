#include "triangle_soup.hpp"

#include <map>

#include "sutura/engine/errors.hpp"

namespace sutura::engine::detail {

TriangleSoup::TriangleSoup(const SurfaceMesh& mesh)
    : positions_(mesh.positions()),
      faces_(mesh.faces()),
      faces_of_parent_(mesh.num_faces()),
      maps_(EditMaps::identity(mesh.num_vertices(), mesh.num_faces())) {
  edge_face_.reserve(3 * faces_.size());
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    faces_of_parent_[f].push_back(static_cast<int>(f));
    for (int k = 0; k < 3; ++k) edge_face_[key(faces_[f][k], faces_[f][(k + 1) % 3])] = int(f);
  }
}

int TriangleSoup::face_with_edge(int u, int v) const {
  const auto it = edge_face_.find(key(u, v));
  return it == edge_face_.end() ? -1 : it->second;
}

int TriangleSoup::add_vertex(const Vec3& p, const std::vector<int>& from,
                             const std::vector<double>& w) {
  // Expand the origins of the soup vertices into origins in the original mesh, summing the
  // weights of shared parents (ordered map: deterministic parent order).
  std::map<std::int32_t, double> acc;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const VertexOrigin& o = maps_.vertices[from[i]];
    for (std::size_t j = 0; j < o.parents.size(); ++j) acc[o.parents[j].value] += w[i] * o.weights[j];
  }
  VertexOrigin origin;
  origin.kind = VertexOriginKind::Interpolated;
  for (const auto& [id, weight] : acc) {
    if (weight == 0.0) continue;
    origin.parents.emplace_back(id);
    origin.weights.push_back(weight);
  }
  if (origin.parents.size() == 1) origin.kind = VertexOriginKind::Copy;
  positions_.push_back(p);
  maps_.vertices.push_back(std::move(origin));
  return static_cast<int>(positions_.size() - 1);
}

void TriangleSoup::set_face(int f, const FaceIndices& idx, const Eigen::Matrix3d& bary) {
  for (int k = 0; k < 3; ++k) {
    const auto it = edge_face_.find(key(faces_[f][k], faces_[f][(k + 1) % 3]));
    if (it != edge_face_.end() && it->second == f) edge_face_.erase(it);
  }
  faces_[f] = idx;
  maps_.faces[f].bary = bary;
  for (int k = 0; k < 3; ++k) edge_face_[key(idx[k], idx[(k + 1) % 3])] = f;
}

int TriangleSoup::add_face(const FaceIndices& idx, FaceId parent, const Eigen::Matrix3d& bary) {
  const int f = static_cast<int>(faces_.size());
  faces_.push_back(idx);
  maps_.faces.push_back(FaceOrigin{parent, bary});
  faces_of_parent_[parent.index()].push_back(f);
  for (int k = 0; k < 3; ++k) edge_face_[key(idx[k], idx[(k + 1) % 3])] = f;
  return f;
}

int TriangleSoup::split_edge(int u, int v, double t) {
  const int fuv = face_with_edge(u, v);
  const int fvu = face_with_edge(v, u);
  if (fuv < 0 && fvu < 0)
    throw InvalidArgument("split_edge: vertices " + std::to_string(u) + " and " +
                          std::to_string(v) + " are not joined by an edge");
  const int w = add_vertex((1.0 - t) * positions_[u] + t * positions_[v], {u, v}, {1.0 - t, t});
  // Split face f holding directed edge a -> b (s = parameter of w from a): (a, b, c) becomes
  // (a, w, c) in place and (w, b, c) appended; both keep the corner order, hence orientation.
  auto split = [&](int f, int a, double s) {
    const FaceIndices old = faces_[f];
    int k = 0;
    while (old[k] != a) ++k;
    const Eigen::Matrix3d B = maps_.faces[f].bary;
    const Eigen::RowVector3d bw = (1.0 - s) * B.row(k) + s * B.row((k + 1) % 3);
    FaceIndices f1 = old, f2 = old;
    Eigen::Matrix3d B1 = B, B2 = B;
    f1[(k + 1) % 3] = w;
    B1.row((k + 1) % 3) = bw;
    f2[k] = w;
    B2.row(k) = bw;
    set_face(f, f1, B1);
    add_face(f2, maps_.faces[f].parent, B2);
  };
  if (fuv >= 0) split(fuv, u, t);
  if (fvu >= 0) split(fvu, v, 1.0 - t);
  return w;
}

int TriangleSoup::split_face(int f, const Eigen::Vector3d& b) {
  const FaceIndices old = faces_[f];
  const int w = add_vertex(b[0] * positions_[old[0]] + b[1] * positions_[old[1]] +
                               b[2] * positions_[old[2]],
                           {old[0], old[1], old[2]}, {b[0], b[1], b[2]});
  const Eigen::Matrix3d B = maps_.faces[f].bary;
  const Eigen::RowVector3d bw = b.transpose() * B;
  const FaceId parent = maps_.faces[f].parent;
  for (int k = 0; k < 3; ++k) {
    FaceIndices idx = old;
    Eigen::Matrix3d Bk = B;
    idx[(k + 2) % 3] = w;
    Bk.row((k + 2) % 3) = bw;
    if (k == 0)
      set_face(f, idx, Bk);
    else
      add_face(idx, parent, Bk);
  }
  return w;
}

int TriangleSoup::locate(FaceId parent, const Eigen::Vector3d& b, Eigen::Vector3d& local) const {
  int best = -1;
  double best_min = -1e-9;
  for (const int f : faces_of_parent_[parent.index()]) {
    // Rows of B are the corners' coordinates in the parent: b^T = l^T B.
    const Eigen::Matrix3d& B = maps_.faces[f].bary;
    const Eigen::Vector3d l = B.transpose().fullPivLu().solve(b);
    if (l.minCoeff() > best_min) {
      best_min = l.minCoeff();
      best = f;
      local = l;
    }
  }
  return best;
}

SurfaceMesh TriangleSoup::build(EditMaps& maps) && {
  maps = std::move(maps_);
  return SurfaceMesh(std::move(positions_), std::move(faces_));
}

}  // namespace sutura::engine::detail
