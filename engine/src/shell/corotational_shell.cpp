// Model 1: corotational flat shell triangle, 6 DOF per node (ANDES-OPT membrane with drilling
// freedoms + DKT bending, element-independent corotational formulation).
//
// Per element: the linear local stiffness K_e (18x18, per corner u v w theta_x theta_y theta_z)
// = ANDES-OPT membrane (andes_membrane.hpp, scales with t) + DKT bending (dkt_bending.hpp,
// scales with t^3), built from the element's own rest geometry (ElementRest) and kept in a
// transparent memo keyed by that geometry and the material (element_stiffness_cache.hpp), so
// the model stays a pure function of its inputs while the rest state changes during relaxation.
// The corotational kinematics, gradient and consistent tangent are in corotation.hpp.
//
// Cost per element, one core (Release, SSE2, measured on the 20k-element tube of the report):
// stiffness 0.9 us (once per rest state, cached), energy 1.5 us, energy + gradient 1.9 us,
// + consistent tangent and its 324 triplets 5.5 us (each including the stiffness; measured
// before the cache). A current triangle collapsed to a segment has no frame: energy and forces are
// then NaN (solvers test std::isfinite and cut the step).
//
// Parallelism: the per-element loop runs under OpenMP for large meshes; every element writes
// into its own preallocated slot and the slots are summed serially in element order, so the
// results are bit-identical for any thread count.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "corotation.hpp"
#include "dkt_bending.hpp"
#include "element_stiffness_cache.hpp"
#include "parallel_loop.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine {
namespace {

constexpr int kDofs = 6;
constexpr int kElementDofs = 18;

/// Checks the problem and the state once per call; throws InvalidArgument naming the problem.
void check_problem(const ShellProblem& p, const ShellState& s) {
  if (p.faces == nullptr || p.rest == nullptr || p.materials == nullptr ||
      p.face_material == nullptr)
    throw InvalidArgument("corotational shell: ShellProblem has a null pointer");
  const std::size_t F = p.faces->size();
  if (p.rest->elements.size() != F)
    throw InvalidArgument("corotational shell: rest state has " +
                          std::to_string(p.rest->elements.size()) + " elements for " +
                          std::to_string(F) + " faces");
  if (p.face_material->size() != F)
    throw InvalidArgument("corotational shell: face_material has " +
                          std::to_string(p.face_material->size()) + " entries for " +
                          std::to_string(F) + " faces");
  if (s.x.size() != p.num_nodes || s.D.size() != p.num_nodes)
    throw InvalidArgument("corotational shell: state has " + std::to_string(s.x.size()) +
                          " positions and " + std::to_string(s.D.size()) + " triads for " +
                          std::to_string(p.num_nodes) + " nodes");
  for (const ShellMaterial& m : *p.materials) validate(m);
  for (std::size_t f = 0; f < F; ++f) {
    const int mi = (*p.face_material)[f];
    if (mi < 0 || static_cast<std::size_t>(mi) >= p.materials->size())
      throw InvalidArgument("corotational shell: face " + std::to_string(f) +
                            " has material index " + std::to_string(mi) + " (have " +
                            std::to_string(p.materials->size()) + " materials)");
    for (const auto v : (*p.faces)[f])
      if (v < 0 || static_cast<std::size_t>(v) >= p.num_nodes)
        throw InvalidArgument("corotational shell: face " + std::to_string(f) +
                              " references node " + std::to_string(v) + " (have " +
                              std::to_string(p.num_nodes) + ")");
  }
}

/// Eigenvalues (ascending) of the symmetric 2x2 tensor [[a, b], [b, c]].
Eigen::Vector2d symmetric_eigenvalues(double a, double b, double c) {
  const double mean = 0.5 * (a + c);
  const double r = std::hypot(0.5 * (a - c), b);
  return {mean - r, mean + r};
}

/// Everything one element needs: rest data and stiffness (cached or its own), corotated
/// state, local forces.
struct ElementState {
  const ElementRestData* data = nullptr;
  ElementRestData own;  ///< used when the call has no cache
  CorotatedElement co;
  LocalForces f;
  double energy = 0.0;
};

/// Evaluates element `f`, with its rest data from `cache` when given; returns false for a
/// degenerate rest triangle, leaving the other fields unset.
bool evaluate_element(const ShellProblem& p, const ShellState& s, std::size_t f,
                      ElementStiffnessCache* cache, ElementState& el) {
  const FaceIndices& face = (*p.faces)[f];
  const ElementRest& rest = p.rest->elements[f];
  const ShellMaterial& material = (*p.materials)[(*p.face_material)[f]];
  if (cache != nullptr) {
    el.data = cache->get(f, rest, material);
    if (el.data == nullptr) return false;
  } else {
    if (!build_element_rest_data(rest, material, el.own)) return false;
    el.data = &el.own;
  }
  const LocalStiffness& K = el.data->K;
  el.co = corotate(el.data->rest, {s.x[face[0]], s.x[face[1]], s.x[face[2]]},
                   {s.D[face[0]], s.D[face[1]], s.D[face[2]]});
  el.f.fm.noalias() = K.membrane.lazyProduct(el.co.dm);
  el.f.fb.noalias() = K.bending.lazyProduct(el.co.db);
  el.energy = 0.5 * (el.co.dm.dot(el.f.fm) + el.co.db.dot(el.f.fb));
  return true;
}

[[noreturn]] void throw_degenerate(std::size_t f) {
  throw InvalidArgument("corotational shell: rest triangle of face " + std::to_string(f) +
                        " is degenerate (zero area)");
}

/// Runs body(f) for every face, in parallel for large meshes; body returns false for a
/// degenerate rest triangle. Throws after the loop (exceptions must not leave an OpenMP region),
/// naming the lowest such face.
template <class Body>
void for_each_element(std::size_t F, Body&& body) {
  std::vector<unsigned char> bad(F, 0);
  for_each_index(F, [&](std::size_t f) { bad[f] = body(f) ? 0 : 1; });
  for (std::size_t f = 0; f < F; ++f)
    if (bad[f]) throw_degenerate(f);
}

class CorotationalShell final : public ShellModel {
 public:
  [[nodiscard]] std::string name() const override { return "corotational-andes-dkt"; }
  [[nodiscard]] int dofs_per_node() const override { return kDofs; }

  [[nodiscard]] double energy(const ShellProblem& p, const ShellState& s) const override {
    check_problem(p, s);
    const CacheLease lease = lease_cache(p.faces->size());
    std::vector<double> e(p.faces->size());
    for_each_element(e.size(), [&](std::size_t f) {
      ElementState el;
      if (!evaluate_element(p, s, f, lease.cache, el)) return false;
      e[f] = el.energy;
      return true;
    });
    return sum_in_order(e);
  }

  double energy_gradient(const ShellProblem& p, const ShellState& s,
                         Eigen::VectorXd& g) const override {
    check_problem(p, s);
    const CacheLease lease = lease_cache(p.faces->size());
    const std::size_t F = p.faces->size();
    std::vector<double> e(F);
    std::vector<Vec18> ge(F);
    for_each_element(F, [&](std::size_t f) {
      ElementState el;
      if (!evaluate_element(p, s, f, lease.cache, el)) return false;
      e[f] = el.energy;
      corotational_gradient(el.data->rest, el.co, el.data->K, el.f, ge[f], nullptr, false);
      return true;
    });
    scatter_gradient(p, ge, g);
    return sum_in_order(e);
  }

  double energy_gradient_hessian(const ShellProblem& p, const ShellState& s, Eigen::VectorXd& g,
                                 Triplets& K, bool symmetric) const override {
    check_problem(p, s);
    const CacheLease lease = lease_cache(p.faces->size());
    const std::size_t F = p.faces->size();
    std::vector<double> e(F);
    std::vector<Vec18> ge(F);
    constexpr std::size_t kPerElement = kElementDofs * kElementDofs;
    K.resize(F * kPerElement);
    for_each_element(F, [&](std::size_t f) {
      ElementState el;
      if (!evaluate_element(p, s, f, lease.cache, el)) return false;
      e[f] = el.energy;
      Mat18 Ke;
      corotational_gradient(el.data->rest, el.co, el.data->K, el.f, ge[f], &Ke, symmetric);
      const FaceIndices& face = (*p.faces)[f];
      Eigen::Triplet<double>* out = K.data() + f * kPerElement;
      for (int i = 0; i < kElementDofs; ++i) {
        const int row = kDofs * face[i / kDofs] + i % kDofs;
        for (int j = 0; j < kElementDofs; ++j)
          *out++ = Eigen::Triplet<double>(row, kDofs * face[j / kDofs] + j % kDofs, Ke(i, j));
      }
      return true;
    });
    scatter_gradient(p, ge, g);
    return sum_in_order(e);
  }

  [[nodiscard]] ElementMeasures measures(const ShellProblem& p,
                                         const ShellState& s) const override {
    check_problem(p, s);
    const CacheLease lease = lease_cache(p.faces->size());
    const std::size_t F = p.faces->size();
    ElementMeasures out;
    out.membrane_strain.resize(F);
    out.bending_curvature.resize(F);
    out.energy_density.resize(F);
    for_each_element(F, [&](std::size_t f) {
      ElementState el;
      if (!evaluate_element(p, s, f, lease.cache, el)) return false;
      const auto& X = el.data->rest.X;
      const auto& x = el.co.x;
      // Green-Lagrange membrane strain E = 1/2 (F^T F - I), F the in-plane deformation
      // gradient between the rest and current local coordinates.
      Eigen::Matrix2d dX, dx;
      dX << X[1] - X[0], X[2] - X[0];
      dx << x[1] - x[0], x[2] - x[0];
      const Eigen::Matrix2d Fd = dx * dX.inverse();
      const Eigen::Matrix2d E = 0.5 * (Fd.transpose() * Fd - Eigen::Matrix2d::Identity());
      out.membrane_strain[f] = symmetric_eigenvalues(E(0, 0), E(0, 1), E(1, 1))(1);
      // DKT curvature change at the centroid (the curvature field is linear on the element).
      Eigen::Matrix<double, 9, 1> db;  // DKT DOFs (w, theta_x, theta_y); w = 0
      for (int a = 0; a < 3; ++a) db.segment<3>(3 * a) << 0.0, el.co.db.segment<2>(2 * a);
      const Eigen::Vector3d kappa =
          dkt_curvature_matrix(X, Eigen::Vector3d::Constant(1.0 / 3.0)) * db;
      const Eigen::Vector2d k12 = symmetric_eigenvalues(kappa(0), 0.5 * kappa(2), kappa(1));
      out.bending_curvature[f] = std::max(std::abs(k12(0)), std::abs(k12(1)));
      out.energy_density[f] = el.energy / el.data->rest.area;
      return true;
    });
    return out;
  }

 private:
  /// The cache for the duration of one call, or none if another thread is using it.
  struct CacheLease {
    std::unique_lock<std::mutex> lock;
    ElementStiffnessCache* cache = nullptr;
  };
  CacheLease lease_cache(std::size_t F) const {
    CacheLease l{std::unique_lock<std::mutex>(cache_.mutex, std::try_to_lock)};
    if (l.lock.owns_lock()) {
      cache_.resize(F);
      l.cache = &cache_;
    }
    return l;
  }

  mutable ElementStiffnessCache cache_;

  static double sum_in_order(const std::vector<double>& e) {
    double total = 0.0;
    for (const double v : e) total += v;
    return total;
  }

  static void scatter_gradient(const ShellProblem& p, const std::vector<Vec18>& ge,
                               Eigen::VectorXd& g) {
    g.setZero(static_cast<Eigen::Index>(p.num_nodes * kDofs));
    for (std::size_t f = 0; f < ge.size(); ++f) {
      const FaceIndices& face = (*p.faces)[f];
      for (int a = 0; a < 3; ++a) g.segment<kDofs>(kDofs * face[a]) += ge[f].segment<kDofs>(kDofs * a);
    }
  }
};

}  // namespace

std::unique_ptr<ShellModel> make_corotational_shell() {
  return std::make_unique<CorotationalShell>();
}

}  // namespace sutura::engine
