// Model 2: discrete shell with 3 translational DOFs per node.
//
//   energy = sum_f [ W_membrane(f) + W_bending(f) ]
//   W_membrane: CST St.Venant-Kirchhoff against the face's rest triangle (cst_membrane.hpp).
//   W_bending:  1/2 dtheta_f^T S_f dtheta_f over the dihedral-angle changes of the face's
//               hinges, plate-consistent coefficients (hinge_bending.hpp); dtheta = theta -
//               theta_rest wrapped to (-pi, pi], theta_rest from the two faces' per-element
//               rest data only (dihedral_angle.hpp: rest_dihedral_angle).
// Nothing per-vertex is read from the rest state, so faces sharing a node may have different
// rest geometry (joins) and the node triads D of the state are ignored.
//
// Evaluation (deterministic: every hinge and face writes only its own slot, in parallel above
// 512 of them; sums are taken in face order): (A) per hinge: angle change and its gradient;
// (B) per face: moments m_f = S_f dtheta_f, membrane energy and gradient; (C) per face: local
// gradient and 18x18 Hessian on the stencil (3 corners + up to 3 apexes across its edges),
//   H_f = H_membrane + J^T S_f J + sum_{hinges owned by f} (m_f,k + m_g,k') d2theta,
// each hinge's d2theta is evaluated once, by hinge.face[0]. The Hessian is exact and symmetric,
// so ShellModel's `symmetric` flag does not change it; K is replaced (up to 324 triplets per
// face). The hinge topology (O(F log F)), the faces' rest data and the hinges' rest angles are
// kept between calls while their inputs are bitwise unchanged (discrete_rest_cache.hpp). Cost
// then O(F): energy and gradient about 0.4 us per face on one thread (BM_Gradient, 5k-face
// tube: 1.9 ms on one thread, 1.0 ms on two), the Hessian about 4 us per face.
#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>
#include <string>

#include "cst_membrane.hpp"
#include "dihedral_angle.hpp"
#include "discrete_rest_cache.hpp"
#include "hinge_bending.hpp"
#include "hinge_topology.hpp"
#include "parallel_loop.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine {

namespace {

using dshell::DiscreteRestCache;
using dshell::DiscreteRestData;
using dshell::FaceStencil;
using dshell::HingeTopology;
using dshell::Mat12;
using dshell::Mat9;
using dshell::Vec12;
using dshell::Vec9;
using Vec18 = Eigen::Matrix<double, 18, 1>;
using Mat18 = Eigen::Matrix<double, 18, 18>;

constexpr double kTwoPi = 2.0 * std::numbers::pi;

void check_problem(const ShellProblem& p, const ShellState& s) {
  auto fail = [](const std::string& what) { throw InvalidArgument("discrete shell: " + what); };
  if (p.faces == nullptr || p.rest == nullptr || p.materials == nullptr ||
      p.face_material == nullptr) {
    fail("the problem is missing faces, rest state, materials or face materials");
  }
  const std::size_t nf = p.faces->size();
  if (p.rest->elements.size() != nf) {
    fail("rest state has " + std::to_string(p.rest->elements.size()) + " elements for " +
         std::to_string(nf) + " faces");
  }
  if (p.face_material->size() != nf) {
    fail(std::to_string(p.face_material->size()) + " face materials for " + std::to_string(nf) +
         " faces");
  }
  if (s.x.size() != p.num_nodes) {
    fail("state has " + std::to_string(s.x.size()) + " positions for " +
         std::to_string(p.num_nodes) + " nodes");
  }
  for (const ShellMaterial& m : *p.materials) validate(m);
  for (std::size_t f = 0; f < nf; ++f) {
    const FaceIndices& v = (*p.faces)[f];
    for (int k = 0; k < 3; ++k) {
      if (v[k] < 0 || static_cast<std::size_t>(v[k]) >= p.num_nodes) {
        fail("face " + std::to_string(f) + " references node " + std::to_string(v[k]) +
             " outside [0, " + std::to_string(p.num_nodes) + ")");
      }
    }
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      fail("face " + std::to_string(f) + " repeats a node");
    }
    const int mat = (*p.face_material)[f];
    if (mat < 0 || static_cast<std::size_t>(mat) >= p.materials->size()) {
      fail("face " + std::to_string(f) + " has material index " + std::to_string(mat) +
           " outside [0, " + std::to_string(p.materials->size()) + ")");
    }
    const auto& X = p.rest->elements[f].X;
    const double scale = std::max({(X[1] - X[0]).squaredNorm(), (X[2] - X[1]).squaredNorm(),
                                   (X[0] - X[2]).squaredNorm()});
    const double twice_area = (X[1] - X[0]).cross(X[2] - X[0]).norm();
    if (!(twice_area > 1e-12 * scale)) fail("rest element " + std::to_string(f) + " is degenerate");
  }
}

class Evaluation {
 public:
  Evaluation(const ShellProblem& p, const ShellState& s, const DiscreteRestData& rest,
             bool with_gradient)
      : p_(p), s_(s), faces_(*p.faces), rd_(rest), topo_(rest.topo) {
    evaluate_hinges(with_gradient);
    evaluate_faces(with_gradient);
  }

  [[nodiscard]] double energy() const {
    double total = 0.0;
    for (std::size_t f = 0; f < faces_.size(); ++f) total += face_energy(f);
    return total;
  }

  void gradient(Eigen::VectorXd& g) const {
    std::vector<Vec18> gl(faces_.size());
    for_each_index(faces_.size(),
                   [&](std::size_t f) { local_gradient_hessian(f, gl[f], nullptr); });
    scatter_gradient(gl, g);
  }

  void gradient_hessian(Eigen::VectorXd& g, Triplets& K) const {
    // Each face owns a fixed range of triplets: 9 per pair of its stencil nodes.
    std::vector<std::size_t> offset(faces_.size() + 1, 0);
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const auto n = static_cast<std::size_t>(rd_.stencil[f].size);
      offset[f + 1] = offset[f] + 9 * n * n;
    }
    K.resize(offset.back());
    std::vector<Vec18> gl(faces_.size());
    for_each_index(faces_.size(), [&](std::size_t f) {
      Mat18 hl;
      local_gradient_hessian(f, gl[f], &hl);
      std::size_t out = offset[f];
      const FaceStencil& st = rd_.stencil[f];
      for (int r = 0; r < st.size; ++r) {
        for (int c = 0; c < st.size; ++c) {
          for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
              K[out++] = Eigen::Triplet<double>(3 * st.node[r] + i, 3 * st.node[c] + j,
                                                hl(3 * st.slot[r] + i, 3 * st.slot[c] + j));
            }
          }
        }
      }
    });
    scatter_gradient(gl, g);
  }

  [[nodiscard]] ElementMeasures measures() const {
    ElementMeasures m;
    const std::size_t nf = faces_.size();
    m.membrane_strain.resize(nf);
    m.bending_curvature.resize(nf);
    m.energy_density.resize(nf);
    for_each_index(nf, [&](std::size_t f) {
      m.membrane_strain[f] = dshell::cst_max_principal_strain(rd_.cst[f], corners(f));
      m.bending_curvature[f] = dshell::max_curvature_change(rd_.bending[f], face_dtheta_[f]);
      m.energy_density[f] = face_energy(f) / rd_.cst[f].area;
    });
    return m;
  }

 private:
  // (A) Angle change of every hinge, optionally with its gradient.
  void evaluate_hinges(bool with_gradient) {
    const std::size_t nh = topo_.hinges.size();
    hinge_dtheta_.resize(nh);
    if (with_gradient) hinge_grad_.resize(nh);
    for_each_index(nh, [&](std::size_t h) {
      const dshell::Hinge& hg = topo_.hinges[h];
      const double theta = dshell::dihedral_angle(
          s_.x[hg.node[0]], s_.x[hg.node[1]], s_.x[hg.node[2]], s_.x[hg.node[3]],
          with_gradient ? &hinge_grad_[h] : nullptr, nullptr);
      hinge_dtheta_[h] = std::remainder(theta - rd_.theta_rest[h], kTwoPi);
    });
  }

  // (B) Per-face hinge-angle changes, bending moments, membrane energies and optionally the
  // membrane gradients.
  void evaluate_faces(bool with_gradient) {
    const std::size_t nf = faces_.size();
    face_dtheta_.resize(nf);
    face_moment_.resize(nf);
    membrane_energy_.resize(nf);
    if (with_gradient) membrane_grad_.resize(nf);
    for_each_index(nf, [&](std::size_t f) {
      for (int k = 0; k < 3; ++k) {
        const std::int32_t h = topo_.face_hinge[f][k];
        face_dtheta_[f][k] = h >= 0 ? hinge_dtheta_[h] : 0.0;
      }
      face_moment_[f] = rd_.bending[f].S * face_dtheta_[f];
      Vec9* grad = with_gradient ? &membrane_grad_[f] : nullptr;
      membrane_energy_[f] = dshell::cst_energy(rd_.cst[f], corners(f), grad, nullptr);
    });
  }

  [[nodiscard]] double face_energy(std::size_t f) const {
    return membrane_energy_[f] + 0.5 * face_dtheta_[f].dot(face_moment_[f]);
  }

  [[nodiscard]] std::array<Vec3, 3> corners(std::size_t f) const {
    const FaceIndices& v = faces_[f];
    return {s_.x[v[0]], s_.x[v[1]], s_.x[v[2]]};
  }

  // (C) Gradient and (optionally) Hessian of face f's energy on its 18-DOF stencil.
  // Requires the evaluation's gradients (with_gradient).
  void local_gradient_hessian(std::size_t f, Vec18& gl, Mat18* hl) const {
    const FaceStencil& st = rd_.stencil[f];
    // Bending part J^T m_f, J = rows of the face's hinge-angle gradients on the stencil, summed
    // hinge by hinge (only 4 of J's 18 columns per row are nonzero).
    Vec18 bending = Vec18::Zero();
    for (int k = 0; k < 3; ++k) {
      const std::int32_t h = topo_.face_hinge[f][k];
      if (h < 0) continue;
      const auto slots = dshell::hinge_slots(k, st.side[k]);
      for (int q = 0; q < 4; ++q)
        bending.segment<3>(3 * slots[q]) += face_moment_[f][k] * hinge_grad_[h].segment<3>(3 * q);
    }
    gl.head<9>() = membrane_grad_[f] + bending.head<9>();
    gl.tail<9>() = bending.tail<9>();
    if (hl == nullptr) return;

    Vec9 gm;
    Mat9 hm;
    dshell::cst_energy(rd_.cst[f], corners(f), &gm, &hm);
    Eigen::Matrix<double, 3, 18> J = Eigen::Matrix<double, 3, 18>::Zero();
    for (int k = 0; k < 3; ++k) {
      const std::int32_t h = topo_.face_hinge[f][k];
      if (h < 0) continue;
      const auto slots = dshell::hinge_slots(k, st.side[k]);
      for (int q = 0; q < 4; ++q) J.block<1, 3>(k, 3 * slots[q]) = hinge_grad_[h].segment<3>(3 * q);
    }
    hl->setZero();
    hl->topLeftCorner<9, 9>() = hm;
    *hl += J.transpose() * rd_.bending[f].S * J;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t h = topo_.face_hinge[f][k];
      if (h < 0 || st.side[k] != 0) continue;
      const dshell::Hinge& hg = topo_.hinges[h];
      const double moment = face_moment_[f][k] + face_moment_[hg.face[1]][hg.halfedge[1]];
      Vec12 grad;
      Mat12 hess;
      dshell::dihedral_angle(s_.x[hg.node[0]], s_.x[hg.node[1]], s_.x[hg.node[2]],
                             s_.x[hg.node[3]], &grad, &hess);
      const auto slots = dshell::hinge_slots(k, 0);
      for (int q = 0; q < 4; ++q) {
        for (int r = 0; r < 4; ++r) {
          hl->block<3, 3>(3 * slots[q], 3 * slots[r]) += moment * hess.block<3, 3>(3 * q, 3 * r);
        }
      }
    }
  }

  // In face order, so the sums do not depend on the number of threads.
  void scatter_gradient(const std::vector<Vec18>& gl, Eigen::VectorXd& g) const {
    g.setZero(static_cast<Eigen::Index>(3 * p_.num_nodes));
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      const FaceStencil& st = rd_.stencil[f];
      for (int i = 0; i < st.size; ++i)
        g.segment<3>(3 * st.node[i]) += gl[f].segment<3>(3 * st.slot[i]);
    }
  }

  const ShellProblem& p_;
  const ShellState& s_;
  const std::vector<FaceIndices>& faces_;
  const DiscreteRestData& rd_;
  const HingeTopology& topo_;
  std::vector<double> hinge_dtheta_;
  std::vector<Vec12> hinge_grad_;
  std::vector<Eigen::Vector3d> face_dtheta_;
  std::vector<Eigen::Vector3d> face_moment_;
  std::vector<double> membrane_energy_;
  std::vector<Vec9> membrane_grad_;
};

class DiscreteShell final : public ShellModel {
 private:
  /// body(rest data) with the memo's data, or with data of its own if another thread holds
  /// the memo (discrete_rest_cache.hpp).
  template <class Body>
  auto with_rest_data(const ShellProblem& p, Body&& body) const {
    std::unique_lock<std::mutex> lock(cache_.mutex, std::try_to_lock);
    if (lock.owns_lock()) return body(cache_.update(p));
    DiscreteRestData own;
    build_discrete_rest_data(p, own);
    return body(own);
  }

  mutable DiscreteRestCache cache_;

 public:
  [[nodiscard]] std::string name() const override { return "discrete-cst-hinge"; }
  [[nodiscard]] int dofs_per_node() const override { return 3; }

  [[nodiscard]] double energy(const ShellProblem& p, const ShellState& s) const override {
    check_problem(p, s);
    return with_rest_data(p, [&](const DiscreteRestData& rd) {
      return Evaluation(p, s, rd, false).energy();
    });
  }

  double energy_gradient(const ShellProblem& p, const ShellState& s,
                         Eigen::VectorXd& g) const override {
    check_problem(p, s);
    return with_rest_data(p, [&](const DiscreteRestData& rd) {
      const Evaluation ev(p, s, rd, true);
      ev.gradient(g);
      return ev.energy();
    });
  }

  double energy_gradient_hessian(const ShellProblem& p, const ShellState& s, Eigen::VectorXd& g,
                                 Triplets& K, bool /*symmetric: always symmetric*/) const override {
    check_problem(p, s);
    return with_rest_data(p, [&](const DiscreteRestData& rd) {
      const Evaluation ev(p, s, rd, true);
      ev.gradient_hessian(g, K);
      return ev.energy();
    });
  }

  [[nodiscard]] ElementMeasures measures(const ShellProblem& p,
                                         const ShellState& s) const override {
    check_problem(p, s);
    return with_rest_data(p, [&](const DiscreteRestData& rd) {
      return Evaluation(p, s, rd, false).measures();
    });
  }
};

}  // namespace

std::unique_ptr<ShellModel> make_discrete_shell() { return std::make_unique<DiscreteShell>(); }

}  // namespace sutura::engine
