#pragma once
// Static equilibrium: Newton-Raphson with load stepping and a backtracking line search on the
// residual norm. Divergence (NaN/inf, energy blow-up, no convergence) rolls the state back to
// the last converged load step, retries with halved load increments, and is reported.
// Where the tangent is not positive definite (Cholmod): with shift_indefinite a
// Levenberg-Marquardt shift; otherwise, under follower pressure, first the tangent without the
// load stiffness (a descent step of the potential, see static_newton.cpp), then LDL^T on the
// true tangent.
#include <functional>
#include <string>
#include <vector>

#include "sutura/engine/sim/linear_solver.hpp"
#include "sutura/engine/sim/shell_system.hpp"
#include "sutura/engine/sim/tangent_assembler.hpp"

namespace sutura::engine {

struct StaticSolverParams {
  /// The loads are scaled by lambda, stepped from lambda_start (where `state` is in
  /// equilibrium, e.g. 0 for an unloaded start or the end factor of a previous solve) to
  /// lambda_end in load_steps equal increments.
  double lambda_start = 0.0;
  double lambda_end = 1.0;
  int load_steps = 1;            ///< >= 1
  double tolerance = 1e-8;       ///< converged when |r| <= tolerance * max(|f_ext|, |r_0|), relative
  int max_iterations = 30;       ///< Newton iterations per load step, >= 1
  /// Safeguard the Newton step: a step that raises |r| more than 1000-fold is refined by
  /// secant steps on du.r; with shift_indefinite (energy minimisation) the step is backtracked
  /// until the Armijo condition on the total potential energy (strain energy minus the work
  /// of the loads, external_work) holds (up to 12 times).
  bool line_search = true;
  int max_step_cuts = 6;         ///< a failed load step is retried with half the increment this often
  double energy_blowup = 1e12;   ///< energy above this factor times the largest energy seen so far = divergence
  /// N*mm, >= 0: floor of the energy scale of the blow-up test. 0 = from the loads (|f| times
  /// the structure's size); set it when a run is driven by something other than loads (the
  /// rest-shape relaxation of a suture drives with no load at all).
  double energy_reference = 0.0;
  /// N, >= 0: floor of the force scale the residual tolerance is relative to (besides |f_ext|
  /// and the first residual). 0 = none. A run that starts at or near equilibrium with no loads
  /// (settling after a relaxation) needs it: relative to a round-off first residual the
  /// tolerance would be unreachable.
  double force_reference = 0.0;
  /// Cholmod only: where the tangent is not positive definite, solve with K + mu diag(K)
  /// (mu from 1e-4, or a decade below the last shift that worked, tenfold until positive
  /// definite; Levenberg-Marquardt) so every step is a
  /// descent direction of the energy. For runs that minimise an energy through instabilities
  /// (the rest-shape relaxation); off for load-driven analyses (benchmarks pass limit points
  /// on the true tangent).
  bool shift_indefinite = false;
  /// With shift_indefinite and Cholmod (energy minimisation): at most this many quasi-Newton
  /// steps per factorisation, >= 0. Such a step reuses the last factorisation (of the tangent
  /// or its shift, at an earlier iterate, or left in the workspace by the previous solve or by
  /// factorize_for_quasi_newton) as the initial inverse Hessian of L-BFGS (20 pairs); it costs
  /// a gradient and a back-substitution instead of a tangent and a factorisation (about 20
  /// times less at 20k elements). A new tangent is factorised when the residual has not
  /// halved over the last 4 quasi-Newton steps, or after this many. 0 = Newton only (every
  /// step with a new tangent).
  int quasi_newton_steps = 30;
  /// Quasi-Newton steps solve with the factorised tangent rounded to single precision
  /// (LinearSolver::solve_approximately): the pairs correct the initial inverse Hessian
  /// anyway, and the solve reads half the bytes (13 against 17 ms at 20k elements). The first
  /// step with each factorisation (Newton steps among them) solves exactly, and the later ones
  /// stay exact when its single-precision solve does not agree (approximate_solve_agrees).
  /// false: every solve exact.
  bool single_precision_solves = true;
  /// A Newton trial state in which a triangle's area falls below this fraction of its rest
  /// area (min_area_ratio) counts as a failed trial, like a non-finite one: the line search
  /// backs off instead of stepping into a collapsed element. In [0, 1); 0 = off.
  double min_area_ratio = 1e-2;
  LinearSolverKind linear_solver = LinearSolverKind::Cholmod;
  PcgParams pcg;
  /// Linear static analysis: one solve K(u0) du = -r(u0) at lambda_end with the stiffness of
  /// the start state (without follower load stiffness), no iteration: the small-displacement
  /// answer of the linear benchmarks.
  bool linear = false;
  /// Asked before every iteration (empty: never); false ends the solve at once, without a
  /// step cut or a retry: the state rolled back to the last converged load step and
  /// StaticResult::stopped set. A time limit inside a long solve.
  std::function<bool()> keep_going;
};

struct NewtonIteration {
  double lambda = 0.0;
  int iteration = 0;
  double residual = 0.0;  ///< |r| over free DOFs
  double energy = 0.0;    ///< internal strain energy, N*mm
  double step_length = 1.0;
  /// N*mm: total potential energy, the strain energy minus the work the loads did since the
  /// start of this load step (external_work); what a line search with shift_indefinite
  /// decreases from iteration to iteration.
  double potential = 0.0;
};

struct StaticResult {
  bool converged = false;
  double lambda_reached = 0.0;  ///< last converged load factor (lambda_end when converged)
  int iterations = 0;           ///< total Newton iterations
  /// Newton iterations whose tangent was not positive definite (Cholmod only: steps taken with
  /// a Levenberg-Marquardt shift, the internal-force tangent or LDL^T). A diagnostic of the
  /// solve, not of the structure: an iterate far from equilibrium (a trial shape with
  /// compressed elements, an unstressed shell under pressure) can be indefinite although every
  /// equilibrium on the way is stable. Whether the equilibrium reached is stable is what
  /// check_stability (stability.hpp) answers.
  int indefinite_iterations = 0;
  /// Steps with a reused factorisation (quasi_newton_steps); `iterations` counts the steps
  /// with a newly factorised tangent.
  int quasi_newton_iterations = 0;
  double residual = 0.0;
  double energy = 0.0;
  std::vector<NewtonIteration> history;
  std::string message;  ///< empty on success; otherwise what went wrong and what was rolled back
  bool stopped = false;  ///< StaticSolverParams::keep_going said no (converged is false)
};

/// What consecutive solves of systems with the same structure can share: the tangent
/// assembler's sparsity pattern and the linear solver with its symbolic factorisation
/// (ordering). Why: a static relaxation runs one solve per increment of s; rebuilding both
/// every time cost about 0.75 s per solve at 20k elements (the pattern 0.65 s, the ordering
/// 0.1 s) against about 0.45 s for one Newton iteration. Both caches re-check the structure on
/// every use, so a workspace may be passed to any system; results are bit-identical with and
/// without one. Not thread-safe: one solve at a time.
class SolverWorkspace {
 public:
  /// The solver of this kind, made on first use and kept while the kind and PCG settings stay.
  LinearSolver& solver(LinearSolverKind kind, const PcgParams& pcg);
  TangentAssembler& assembler() { return assembler_; }
  /// For the tangent without the load stiffness (a triplet structure of its own).
  TangentAssembler& internal_assembler() { return internal_assembler_; }

  /// Marks the solver's current factorisation (if positive definite) as the start of the next
  /// energy minimisation's quasi-Newton steps, for systems of num_free free DOFs.
  void keep_factor(Eigen::Index num_free);
  /// Whether the solver still holds the kept factorisation, for a system of num_free free
  /// DOFs: a solve of a system with another structure, or after anything else factorised
  /// (another LinearSolver::definite_factor_id), factorises anew.
  [[nodiscard]] bool holds_reusable_factor(Eigen::Index num_free) const;

 private:
  std::uint64_t reusable_factor_ = 0;  ///< definite_factor_id of the kept factorisation (0: none)
  Eigen::Index reusable_size_ = -1;    ///< free DOFs of the system it was made for
  TangentAssembler assembler_;
  TangentAssembler internal_assembler_;
  std::unique_ptr<LinearSolver> solver_;
  LinearSolverKind kind_ = LinearSolverKind::Cholmod;
  PcgParams pcg_;
};

/// Factorises the tangent at `state` (Cholmod) and leaves it in `workspace` as the start of the
/// next energy minimisation's quasi-Newton steps (StaticSolverParams::quasi_newton_steps).
/// Why: a relaxation's first increment starts where the rest shape has just moved, so its own
/// tangent is typically indefinite (a Levenberg-Marquardt search of several failed
/// factorisations), while the tangent at the start, a stable equilibrium, is positive
/// definite and close. Returns false (and leaves no factorisation) if it is not positive
/// definite. Cost: one tangent assembly and one factorisation.
bool factorize_for_quasi_newton(const ShellSystem& sys, const ShellState& state, double lambda,
                                SolverWorkspace& workspace);

/// Solves sys for equilibrium starting from `state` (modified in place; on failure it holds the
/// last converged load step). `workspace` (optional) carries the pattern and the ordering from
/// one call to the next. Throws InvalidArgument for invalid parameters.
StaticResult solve_static(const ShellSystem& sys, ShellState& state, const StaticSolverParams& params,
                          SolverWorkspace* workspace = nullptr);

}  // namespace sutura::engine
