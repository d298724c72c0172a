#include "sutura/engine/sim/rigid_modes.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

namespace sutura::engine {

namespace {

std::string text(const Vec3& v) {
  std::ostringstream os;
  const auto r = [](double a) { return std::abs(a) < 5e-4 ? 0.0 : std::round(a * 1000.0) / 1000.0; };
  os << "(" << r(v.x()) << ", " << r(v.y()) << ", " << r(v.z()) << ")";
  return os.str();
}

}  // namespace

std::string RigidMotion::describe() const {
  if (rotation.norm() == 0.0) return "translation along " + text(translation.normalized());
  return "rotation about the axis " + text(rotation.normalized()) + " through " + text(point);
}

std::vector<RigidMotion> free_rigid_motions(const std::vector<Vec3>& x, const Constraints& c) {
  if (x.empty()) return {};
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : x) centre += p;
  centre /= double(x.size());
  double size = 0.0;  // rms distance from the centre
  for (const Vec3& p : x) size += (p - centre).squaredNorm();
  size = std::sqrt(size / double(x.size()));
  if (!(size > 0.0)) size = 1.0;
  // Unknowns: translation t and size * rotation w. A fixed translation DOF d at node v gives
  // the row e_d . (t + w x r) = e_d . t + w . (r x e_d), r = (x_v - centre) / size; a fixed
  // rotation DOF d the row e_d . w (in units of 1/size: a held rotation is as strong as a held
  // node at the body's size). AtA accumulates the rows.
  Eigen::Matrix<double, 6, 6> AtA = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t v = 0; v < x.size() && v < c.fixed.size(); ++v) {
    if (c.fixed[v] == 0) continue;
    const Vec3 r = (x[v] - centre) / size;
    for (int d = 0; d < 6; ++d) {
      if (!c.is_fixed(v, d)) continue;
      Eigen::Matrix<double, 6, 1> row = Eigen::Matrix<double, 6, 1>::Zero();
      row(d) = 1.0;
      if (d < 3) row.tail<3>() = r.cross(Vec3::Unit(d));
      AtA += row * row.transpose();
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(AtA);
  std::vector<RigidMotion> free;
  for (int k = 0; k < 6; ++k) {
    if (!(eig.eigenvalues()(k) < 1e-12)) continue;  // singular value below 1e-6
    const Eigen::Matrix<double, 6, 1> u = eig.eigenvectors().col(k);
    RigidMotion m;
    m.translation = u.head<3>();
    m.rotation = u.tail<3>() / size;
    if (u.tail<3>().norm() < 1e-9) {
      m.rotation.setZero();
    } else {
      // About the centre the field is t + w x (x - c). About the axis (the points whose
      // velocity is along w, p = c + (w x t) / |w|^2) it is t_par + w x (x - p), t_par the
      // part of t along w (a screw's advance).
      m.point = centre + m.rotation.cross(m.translation) / m.rotation.squaredNorm();
      m.translation = m.translation.dot(m.rotation) / m.rotation.squaredNorm() * m.rotation;
    }
    free.push_back(m);
  }
  return free;
}

}  // namespace sutura::engine
