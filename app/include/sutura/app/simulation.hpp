#pragma once
// Runs the engine's solvers on workspace objects. Several objects are simulated together by
// merging them into one ShellSystem with disjoint node ranges (so contact between them can be
// added as one more term), and the result is written back to each object.
#include <memory>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sutura/app/workspace.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/sim/area_barrier.hpp"
#include "sutura/engine/sim/contact.hpp"
#include "sutura/engine/sim/dynamics.hpp"
#include "sutura/engine/sim/static_solver.hpp"
#include "sutura/engine/surgery/relaxation.hpp"

namespace sutura::app {

/// "corotational" (default, 6 DOF) | "discrete" (3 DOF); throws std::invalid_argument.
std::unique_ptr<engine::ShellModel> make_model(const std::string& name);

/// The shell model whose run produced the object's current state (SurfaceAttributes::
/// state_model), Model 1 (corotational) before any run: what its strain, bending and energy
/// fields are measured with.
std::unique_ptr<engine::ShellModel> state_model_of(const SceneObject& obj);

/// What to change after a relaxation (to s = `until`) failed with the engine's `message`
/// under these settings, in plain words with the session field and the window's control that
/// change it ("Advice: ...", one or two sentences), or empty when the message names no cause
/// it can advise on. Collapsing or exploding elements: first the collapse barrier; with it, a
/// static relaxation to 1 is advised the flap method (static part of the way, then damped
/// dynamics), one that stops short of 1 (the flap method's first part) an earlier switch to
/// dynamics; with dynamics too, the plan itself. No Newton convergence: more increments or
/// iterations. A singular tangent stiffness: hold the object.
std::string relaxation_advice(const std::string& message, bool collapse_barrier,
                              engine::RelaxationSolver solver, double until);

/// What to change after a static solve failed with `message` (engine::StaticResult::message)
/// as Newton's iteration (`minimize` false), in the words of relaxation_advice, or empty. A
/// state that exploded, collapsed or did not converge: solve as an energy minimisation, whose
/// steps only go downhill, when the loads have a potential (`conservative`: no pressure ends
/// at a free rim); otherwise hold the free rims first. Nothing for a minimisation that failed,
/// nor for other messages.
std::string solve_advice(const std::string& message, bool minimize, bool conservative);

/// Whether the loads on the named objects of `workspace` (all of them when `objects` is
/// empty), solved together at full value, have a potential energy: no pressure ends at a rim
/// free to move (free_pressure_rims). Then a static solve of them can be an energy
/// minimisation ("minimize"). Throws std::invalid_argument for an unknown object.
/// Cost O(F log F), on copies of the objects.
bool loads_have_potential(const Workspace& workspace, const std::vector<std::string>& objects = {});

/// Whether no rigid-body motion of the object is free (engine::free_rigid_motions of its
/// state and constraints): a static solve of it has a unique equilibrium. Contact with another
/// object is not counted. O(V).
bool restrained(const SceneObject& object);

class MergedSystem {
 public:
  /// Merges `objects` (non-empty, distinct). Pending loads are scaled by lambda, applied
  /// loads are constant. Throws std::invalid_argument for moments with a 3-DOF model.
  /// With `contact` and at least two objects, a penalty contact term between every pair of
  /// objects is added to the system (no self-contact); engine::InvalidArgument for invalid
  /// contact parameters.
  /// With `barrier`, an engine::AreaBarrier over all faces is added too.
  MergedSystem(const std::vector<SceneObject*>& objects, const engine::ShellModel& model,
               const engine::ContactParams* contact = nullptr,
               const engine::AreaBarrierParams* barrier = nullptr);

  [[nodiscard]] const engine::ShellSystem& system() const { return system_; }
  /// The merged rest state the system points at (a relaxation rewrites it as it runs).
  engine::RestState& rest() { return rest_; }
  /// Merged y0 for a relaxation: each object's pending relax_from, or its rest where it has
  /// none (nothing to relax there: y0 = x0).
  [[nodiscard]] engine::RestState relax_from() const;
  engine::ShellState& state() { return state_; }
  Eigen::VectorXd& velocity() { return velocity_; }
  /// Copies the merged state (and velocity) back into every object and its mesh positions.
  void write_back();
  /// Each object's name with its slice of merged positions `x` (e.g. a running state's x).
  [[nodiscard]] std::vector<std::pair<std::string, std::span<const engine::Vec3>>>
  positions_by_object(const std::vector<engine::Vec3>& x) const;

 private:
  std::vector<SceneObject*> objects_;
  std::vector<std::size_t> node_offset_;
  std::vector<engine::FaceIndices> faces_;
  engine::RestState rest_;
  std::vector<engine::ShellMaterial> materials_;
  std::vector<int> face_material_;
  engine::ShellSystem system_;
  std::unique_ptr<engine::ContactTerm> contact_;  ///< in system_.terms when present
  std::unique_ptr<engine::AreaBarrier> barrier_;  ///< in system_.terms when present
  engine::ShellState state_;
  Eigen::VectorXd velocity_;
};

/// The merged nodes (sorted) at which a pressure of the system's loads or fixed loads ends at a
/// rim free to move (engine::free_pressure_rim): where the loads have no potential energy.
/// Cost O(F log F).
std::set<std::size_t> free_pressure_rims(const MergedSystem& merged);


}  // namespace sutura::app
