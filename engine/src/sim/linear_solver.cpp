#include "sutura/engine/sim/linear_solver.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include "blas_threads.hpp"
#include "parallel_cholesky.hpp"
#include "serial_openmp.hpp"
#include "single_precision_factor.hpp"
#include "sutura/engine/errors.hpp"

namespace sutura::engine {

using SpMat = Eigen::SparseMatrix<double>;

LinearSolverKind parse_linear_solver(const std::string& name) {
  if (name == "cholmod") return LinearSolverKind::Cholmod;
  if (name == "ldlt") return LinearSolverKind::Ldlt;
  if (name == "pcg") return LinearSolverKind::Pcg;
  throw InvalidArgument("unknown linear solver '" + name + "' (cholmod, ldlt, pcg)");
}

std::string to_string(LinearSolverKind k) {
  switch (k) {
    case LinearSolverKind::Cholmod: return "cholmod";
    case LinearSolverKind::Ldlt: return "ldlt";
    case LinearSolverKind::Pcg: return "pcg";
  }
  return "?";
}

namespace {

// True when A has the same sparsity pattern as the one analysed last (then the symbolic
// factorisation, the expensive ordering step, is reused).
class PatternCache {
 public:
  bool same(const SpMat& A) {
    const auto* outer = A.outerIndexPtr();
    const auto* inner = A.innerIndexPtr();
    const bool same = rows_ == A.rows() && nnz_ == A.nonZeros() &&
                      std::equal(outer, outer + A.outerSize() + 1, outer_.begin(), outer_.end()) &&
                      std::equal(inner, inner + A.nonZeros(), inner_.begin(), inner_.end());
    if (!same) {
      rows_ = A.rows();
      nnz_ = A.nonZeros();
      outer_.assign(outer, outer + A.outerSize() + 1);
      inner_.assign(inner, inner + A.nonZeros());
    }
    return same;
  }

 private:
  Eigen::Index rows_ = -1, nnz_ = -1;
  std::vector<int> outer_, inner_;
};

class LdltSolver final : public LinearSolver {
 public:
  bool factorize(const SpMat& A) override {
    if (!cache_.same(A)) ldlt_.analyzePattern(A);
    ldlt_.factorize(A);
    return ldlt_.info() == Eigen::Success;
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = ldlt_.solve(b);
    return ldlt_.info() == Eigen::Success && x.allFinite();
  }

 private:
  Eigen::SimplicialLDLT<SpMat, Eigen::Lower> ldlt_;
  PatternCache cache_;
};

// Eigen's supernodal LL^T with its CHOLMOD factor readable (for the single-precision copy).
class SupernodalLlt : public Eigen::CholmodSupernodalLLT<SpMat, Eigen::Lower> {
 public:
  [[nodiscard]] const cholmod_factor* factor() const { return m_cholmodFactor; }
  // For a numeric factorisation done outside CHOLMOD into its factor (ParallelCholesky).
  [[nodiscard]] cholmod_factor* mutable_factor() { return m_cholmodFactor; }
  void set_factorised(bool ok) {
    m_info = ok ? Eigen::Success : Eigen::NumericalIssue;
    m_factorizationIsOk = true;
  }
};

class CholmodSolver final : public LinearSolver {
 public:
  // CHOLMOD prints a warning for every indefinite matrix; the fallback is reported through
  // last_note() instead, so its own printing is switched off.
  CholmodSolver() { llt_.cholmod().print = 0; }
  bool factorize(const SpMat& A) override {
    note_.clear();
    single_current_ = false;
    cholesky(A);
    use_fallback_ = llt_.info() != Eigen::Success;
    id_ = use_fallback_ ? 0 : ++count_;
    if (!use_fallback_) return true;
    // Not positive definite (compression near buckling, or far from equilibrium): LDL^T
    // handles symmetric indefinite matrices with non-zero pivots.
    note_ = "cholmod: matrix not positive definite, used LDL^T";
    return fallback_.factorize(A);
  }
  bool factorize_definite(const SpMat& A) override {
    note_.clear();
    single_current_ = false;
    cholesky(A);
    use_fallback_ = false;
    const bool ok = llt_.info() == Eigen::Success;
    id_ = ok ? ++count_ : 0;
    if (ok) return true;
    note_ = "cholmod: matrix not positive definite";
    return false;
  }
  bool factorize_indefinite(const SpMat& A) override {
    note_ = "cholmod: matrix not positive definite, used LDL^T";
    use_fallback_ = true;
    id_ = 0;
    return fallback_.factorize(A);
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    if (use_fallback_) return fallback_.solve(b, x);
    const detail::SingleThreadedBlas one_thread;  // why: blas_threads.hpp
    x = llt_.solve(b);
    return llt_.info() == Eigen::Success && x.allFinite();
  }
  bool solve_approximately(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    if (use_fallback_ || llt_.info() != Eigen::Success || llt_.factor() == nullptr)
      return solve(b, x);
    if (!single_current_) {
      single_.assign(*llt_.factor());
      single_current_ = true;
    }
    single_.solve(*llt_.factor(), split_, b, x);
    return x.allFinite();
  }
  [[nodiscard]] std::string last_note() const override { return note_; }
  [[nodiscard]] std::uint64_t definite_factor_id() const override { return id_; }

 private:
  // Factors large enough to pay for a second thread (kParallelFactorEntries) are factorised
  // on two threads (parallel_cholesky.hpp) into CHOLMOD's factor object, its values allocated
  // by converting the symbolic factor after each analysis; smaller ones, and any factor the
  // parallel code cannot take, by CHOLMOD. Which one depends on the pattern only:
  // deterministic. The tree's split, which the two-thread factorisation and the
  // single-precision solves share, is made once per analysis.
  void cholesky(const SpMat& A) {
    if (!cache_.same(A)) {
      const detail::SerialOpenMp serial;  // why: serial_openmp.hpp
      llt_.analyzePattern(A);
      parallel_ = {};
      split_ = {};
      cholmod_factor* L = llt_.mutable_factor();
      if (L != nullptr && L->is_super) split_ = detail::split_supernode_tree(*L);
      if (L != nullptr && L->is_super && L->xsize >= kParallelFactorEntries && A.isCompressed() &&
          cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, L, &llt_.cholmod()) != 0)
        parallel_.prepare(A, *L, split_);
    }
    if (parallel_.prepared() && A.isCompressed()) {
      llt_.set_factorised(parallel_.factorize(A, *llt_.mutable_factor()));
      return;
    }
    const detail::SerialOpenMp serial;  // why: serial_openmp.hpp
    llt_.factorize(A);
  }

  // Below this many factor entries (about 2k elements, a factorisation of a few milliseconds)
  // CHOLMOD's own factorisation is kept. A judgement, not a measured optimum: the parallel
  // factorisation was measured from 5k elements up.
  static constexpr std::size_t kParallelFactorEntries = 300000;

  SupernodalLlt llt_;
  detail::SupernodeSplit split_;  ///< of llt_'s symbolic factor
  detail::ParallelCholesky parallel_;
  detail::SinglePrecisionFactor single_;
  bool single_current_ = false;  ///< single_ holds the current factorisation's values
  LdltSolver fallback_;
  PatternCache cache_;
  bool use_fallback_ = false;
  std::uint64_t count_ = 0;  ///< Cholesky factorisations that succeeded
  std::uint64_t id_ = 0;     ///< definite_factor_id()
  std::string note_;
};

class PcgSolver final : public LinearSolver {
 public:
  explicit PcgSolver(const PcgParams& p) : params_(p) {}
  bool factorize(const SpMat& A) override {
    cg_.setTolerance(params_.tolerance);
    cg_.setMaxIterations(params_.max_iterations);
    cg_.compute(A);
    return cg_.info() == Eigen::Success;
  }
  bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    x = cg_.solve(b);
    note_ = "pcg: " + std::to_string(cg_.iterations()) + " iterations, error " +
            std::to_string(cg_.error());
    return cg_.info() == Eigen::Success && x.allFinite();
  }
  [[nodiscard]] std::string last_note() const override { return note_; }

 private:
  PcgParams params_;
  Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>> cg_;
  std::string note_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind, const PcgParams& pcg) {
  switch (kind) {
    case LinearSolverKind::Cholmod: return std::make_unique<CholmodSolver>();
    case LinearSolverKind::Ldlt: return std::make_unique<LdltSolver>();
    case LinearSolverKind::Pcg: return std::make_unique<PcgSolver>(pcg);
  }
  throw InvalidArgument("unknown linear solver kind");
}

bool approximate_solve_agrees(LinearSolver& solver, const Eigen::VectorXd& b,
                              const Eigen::VectorXd& exact) {
  Eigen::VectorXd x;
  return solver.solve_approximately(b, x) && (x - exact).norm() <= 1e-3 * exact.norm();
}

Eigen::SparseMatrix<double> shift_diagonal(const Eigen::SparseMatrix<double>& A,
                                           const Eigen::VectorXd& scale, double mu) {
  Eigen::SparseMatrix<double> out = A;
  for (Eigen::Index i = 0; i < out.rows(); ++i) out.coeffRef(i, i) += mu * scale[i];
  return out;
}

}  // namespace sutura::engine
