#pragma once
// Sparse symmetric linear solvers for Newton and implicit dynamics, selectable:
//  - Cholmod: supernodal sparse Cholesky (SuiteSparse CHOLMOD, BLAS = OpenBLAS). Symbolic
//    analysis is reused while the sparsity pattern stays the same (all Newton iterations of
//    a run). Falls back to LDL^T when the matrix is not positive definite (buckling, or a
//    compressed state far from equilibrium).
//  - Ldlt: Eigen's simplicial LDL^T (no external dependency).
//  - Pcg: preconditioned conjugate gradient (the paper's choice, Sec. 2.1), incomplete
//    Cholesky preconditioner.
#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Sparse>

namespace sutura::engine {

enum class LinearSolverKind { Cholmod, Ldlt, Pcg };

/// "cholmod" | "ldlt" | "pcg"; throws InvalidArgument otherwise.
LinearSolverKind parse_linear_solver(const std::string& name);
std::string to_string(LinearSolverKind k);

struct PcgParams {
  double tolerance = 1e-10;  ///< relative residual of the linear solve
  int max_iterations = 20000;
};

class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Factorises (or prepares) A (symmetric; full storage). Returns false when the
  /// factorisation fails (singular matrix); the caller reports it.
  virtual bool factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// Like factorize, but fails (returns false) instead of falling back when A is not positive
  /// definite: for callers that shift an indefinite matrix themselves (Levenberg-Marquardt),
  /// where a fallback factorisation would be thrown away. Solvers that cannot tell (Ldlt,
  /// Pcg) just factorise.
  virtual bool factorize_definite(const Eigen::SparseMatrix<double>& A) { return factorize(A); }
  /// Like factorize, for a matrix the caller already knows not to be positive definite (a
  /// factorize_definite of it failed): goes straight to the indefinite path instead of
  /// repeating the failed Cholesky attempt. Solvers without one just factorise.
  virtual bool factorize_indefinite(const Eigen::SparseMatrix<double>& A) { return factorize(A); }
  /// Solves A x = b with the last factorised A. Returns false on failure (PCG not converged).
  virtual bool solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// Like solve, but the answer may carry a relative error of about 1e-6: Cholmod
  /// solves with its factor rounded to single precision (1.3 to 3 times faster: the solve is
  /// bound by reading the factor, single_precision_factor.hpp); the others solve exactly. For
  /// iterations that correct their own steps' error against a residual computed in double
  /// (quasi-Newton steps, modified Newton), never for a step that must be exact. The first call
  /// after a factorisation rounds the factor (O(nnz(L))).
  virtual bool solve_approximately(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    return solve(b, x);
  }
  /// Identifies the current factorisation when it is a Cholesky factorisation of a positive
  /// definite matrix (a new number for every factorisation), 0 otherwise: none yet, a failed
  /// attempt, an indefinite fallback, or a solver that cannot tell. A caller that keeps
  /// solving with an older factorisation (the static solver's quasi-Newton steps) checks with
  /// it that nobody has factorised another matrix since.
  [[nodiscard]] virtual std::uint64_t definite_factor_id() const { return 0; }
  /// What happened in the last call, e.g. "cholmod fell back to LDL^T (not positive definite)".
  [[nodiscard]] virtual std::string last_note() const { return {}; }
};

std::unique_ptr<LinearSolver> make_linear_solver(LinearSolverKind kind, const PcgParams& pcg = {});

/// Whether `solver`'s solve_approximately of A x = b reproduces `exact` (its exact solve of
/// the same system) to a relative 1e-3. Callers ask it once per factorisation, after the
/// exact solve of a fresh factorisation's first step, before relying on approximate solves
/// with that factorisation (a guard: no matrix met so far, nearly singular ones included,
/// failed it; single_precision_factor.hpp). Cost: one approximate solve.
bool approximate_solve_agrees(LinearSolver& solver, const Eigen::VectorXd& b,
                              const Eigen::VectorXd& exact);

/// A + mu diag(scale): the Levenberg-Marquardt shift of a tangent (mu > 0; scale = |diag A|)
/// or its mirror (mu < 0). A must store its whole diagonal (an assembled tangent does).
Eigen::SparseMatrix<double> shift_diagonal(const Eigen::SparseMatrix<double>& A,
                                           const Eigen::VectorXd& scale, double mu);

}  // namespace sutura::engine
