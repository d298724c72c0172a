#pragma once
// Implicit (backward) Euler dynamics with lumped mass and Rayleigh damping C = alpha*M + beta*K.
// Unconditionally stable, numerically dissipative: what "settling" and rest-shape relaxation
// need (paper, Sec. 2.3). Each step solves the nonlinear step equation with a modified Newton
// method that reuses the factorised step matrix across iterations and steps while it still
// converges (see dynamics.cpp), either to a tolerance or, linearized, for one iteration where
// that is safe (DynamicsScheme); the stiffness-proportional damping uses the tangent of the
// last refactorisation at the start of a step, turned with the nodes' rotations since
// (DynamicsParams::corotated_damping).
#include <functional>
#include <string>

#include "sutura/engine/sim/linear_solver.hpp"
#include "sutura/engine/sim/shell_system.hpp"

namespace sutura::engine {

/// How far each step's nonlinear equation is solved.
enum class DynamicsScheme {
  /// Backward Euler proper: Newton iterations until the residual is below `tolerance`,
  /// from the constant-velocity predictor; a step that fails from there is tried once more
  /// from zero increment (to the same tolerance) before it is cut. What the rest-shape
  /// relaxation uses (relaxation.cpp).
  Newton,
  /// Linearly implicit Euler (Baraff & Witkin 1998; SOFA's implicit Euler, the solver of the
  /// paper's prototype), guarded: a step starts from zero increment at the last step's
  /// gradient and ends after its first Newton iteration that halves the residual and does
  /// not raise the total energy (kinetic + strain - work of the loads since the step's
  /// start), which the exact backward Euler step, dissipative, never does; otherwise it
  /// iterates on as Newton (to `tolerance`, relative to the residual at zero increment). One
  /// gradient evaluation and one back-substitution per step where Newton takes 3-5. Why the
  /// guard: stopped at the halving test alone, the heavy strip of the dynamics tests run at
  /// dt = 0.05 s ran away (strain energy 3e8 instead of 9 N*mm). The motion is Newton's to
  /// 3e-6 (swinging strip) and 1e-3 (benchmark tube) of the tip's travel, where halving dt
  /// moves Newton's own by 6 %. The gradient and energy at a step's start are the last
  /// step's, so the hook must not change the system (the rest-shape relaxation, which does,
  /// uses Newton).
  Linearized,
};

struct DynamicsParams {
  /// Linearized by default: on the benchmark tube a step of a running simulation takes 5 ms
  /// instead of Newton's 16 (model 1, 5k elements), and the motion differs from Newton's by
  /// 1e-3 of the travel where backward Euler's own time error is 6 % (docs/performance.md).
  DynamicsScheme scheme = DynamicsScheme::Linearized;
  double dt = 1e-3;            ///< s, > 0
  int steps = 100;             ///< >= 1
  double mass_damping = 10.0;  ///< Rayleigh alpha, 1/s, >= 0
  double stiffness_damping = 1e-3;  ///< Rayleigh beta, s, >= 0
  double tolerance = 1e-6;     ///< Newton tolerance per step, relative to the step's first residual
  int max_iterations = 20;     ///< Newton iterations per step
  /// A failed step is retried as two steps of half the size, recursively, down to
  /// dt / 2^max_step_cuts; in [0, 10].
  int max_step_cuts = 4;
  /// A step that leaves a triangle below this fraction of its rest area (and below where it
  /// started) fails and is retried in halves (see min_area_ratio in shell_system.hpp);
  /// in [0, 1), 0 = off.
  double min_area_ratio = 1e-2;
  /// N, >= 0: floor of the force the step tolerance is relative to (besides the step's first
  /// residual and |f_ext|); 0 = none. Steps taken at equilibrium need it (round-off residual).
  double force_reference = 0.0;
  /// Newton iterations on a reused step matrix solve with its factor rounded to single
  /// precision (LinearSolver::solve_approximately): they are inexact by the matrix's age
  /// anyway and the residual is computed in double; at 5k elements such a solve takes about
  /// a third of the exact one's time. The first iteration on a new matrix solves exactly, and
  /// the reuses stay exact when the single-precision solve of that first step does not agree
  /// with it (approximate_solve_agrees). false: every solve exact.
  bool single_precision_solves = true;
  /// Corotated stiffness damping: the stiffness K_d of the damping term is turned with the
  /// nodes' rotations since it was taken and taken anew once the shell has bent by more than
  /// 3e-3 rad since (engine/src/sim/corotated_damping.hpp), and a reused step matrix is turned
  /// with it. The damping then acts on deformation, not on rigid rotation: a heavy strip
  /// swinging up through a radian settles to its equilibrium, where with the unturned K_d it
  /// still crept, its tip 27 % short, after 2 s. false: K_d is the tangent of the last rebuild
  /// at a step's start, unturned, which damps rigid rotation too; the rest-shape relaxation uses
  /// that (relaxation.cpp): its damping only has to settle the shape, and the unturned matrix
  /// needs far fewer factorisations there (docs/performance.md, "Measurements behind
  /// defaults").
  bool corotated_damping = true;
  LinearSolverKind linear_solver = LinearSolverKind::Cholmod;
  /// Asked before every Newton iteration; false stops the run at once (no step cut), the
  /// state rolled back to the last whole step and DynamicsResult::stopped set. Empty: never.
  /// Bounds a run's overrun of a deadline to one Newton iteration (the per-step hook alone
  /// would let a whole step with all its cuts run past it).
  std::function<bool()> keep_going;
  PcgParams pcg;
};

struct DynamicsState {
  ShellState shell;
  Eigen::VectorXd velocity;  ///< full DOFs (translational mm/s, angular rad/s); empty = at rest
};

struct DynamicsResult {
  bool ok = true;
  int steps_done = 0;
  int newton_iterations = 0;
  int factorizations = 0;       ///< step matrices assembled and factorised
  int step_cuts = 0;            ///< failed (sub-)steps retried as two half steps
  int restarts = 0;  ///< Newton steps that failed from the predictor and converged from zero increment
  double kinetic_energy = 0.0;  ///< N*mm at the end
  double strain_energy = 0.0;   ///< N*mm at the end
  double residual = 0.0;        ///< static residual |g_int - f_ext| at the end (free DOFs)
  std::string message;          ///< why the run stopped early (state rolled back to the last good step)
  bool stopped = false;         ///< DynamicsParams::keep_going said no (ok is false)
};

/// Called before every step with the step index; reports progress, and lets the relaxation
/// update the rest state (the system's problem.rest may be changed through the pointer it
/// owns) — with DynamicsScheme::Newton only: the linearized scheme starts each step from the
/// last step's gradient and energy, which such a change would leave stale. Return false to
/// stop.
using StepHook = std::function<bool(int step)>;

/// Advances `state` by params.steps steps of size dt (a failed step is retried in halves, see
/// max_step_cuts; the hook is called once per step of dt). Divergence (NaN, energy blow-up,
/// Newton failure) that persists at the smallest sub-step rolls back to the last good step and
/// returns ok = false with a message.
DynamicsResult simulate_dynamics(const ShellSystem& sys, DynamicsState& state,
                                 const DynamicsParams& params, const StepHook& hook = {});

}  // namespace sutura::engine
