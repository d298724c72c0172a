#include "sutura/app/simulation.hpp"

#include <algorithm>
#include <stdexcept>

#include "sutura/engine/sim/loads.hpp"
#include "sutura/engine/sim/rigid_modes.hpp"

namespace sutura::app {

std::string relaxation_advice(const std::string& message, bool collapse_barrier,
                              engine::RelaxationSolver solver, double until) {
  const auto says = [&](const char* what) { return message.find(what) != std::string::npos; };
  if (says("collapsed a triangle") || says("non-finite") || says("exploded")) {
    if (!collapse_barrier)
      return "Advice: elements collapse where the relaxation gathers tissue; turn on the collapse "
             "barrier (\"collapse_barrier\": true; in the window: Simulate > Resist collapse "
             "(gathered tissue)), which keeps a triangle from folding through itself.";
    if (solver == engine::RelaxationSolver::Static && until >= 1.0)
      return "Advice: elements collapse even with the collapse barrier; relax statically only "
             "part of the way and the rest as damped dynamics (\"relax\": {\"until\": 0.6} "
             "then {\"solver\": \"dynamic\"}; in the window: Simulate > Static, then damped "
             "dynamics (flap)), whose inertia carries gathered tissue through.";
    if (solver == engine::RelaxationSolver::Static)
      return "Advice: the static part of the relaxation fails before it reaches its end; hand "
             "over to the damped dynamics earlier (a smaller \"relax\": {\"until\": ...} "
             "before the dynamic run), or check the plan as below if that fails too.";
    return "Advice: elements collapse with the barrier and damped dynamics too: the plan "
           "gathers more tissue than the wall can take up. Check that the sutured chains run "
           "the same way and are of similar length, and that a patch is wide enough for the "
           "gap it closes.";
  }
  if (says("no convergence in"))
    return "Advice: relax in more, smaller increments (\"relax\": {\"steps\": ...}; in the "
           "window: Simulate > relax steps), or allow more Newton iterations per increment "
           "(\"relax\": {\"max_iterations\": ...}).";
  if (says("tangent stiffness is singular"))
    return "Advice: the object can move freely; hold it (the fix op; in the window: Plan > Fix "
           "ends).";
  return {};
}

std::string solve_advice(const std::string& message, bool minimize, bool conservative) {
  const auto says = [&](const char* what) { return message.find(what) != std::string::npos; };
  if (minimize || !(says("exploded") || says("collapsed a triangle") || says("non-finite") ||
                    says("no convergence in")))
    return {};
  if (conservative)
    return "Advice: solve as an energy minimisation (\"minimize\": true), whose steps only go "
           "downhill: it converges where Newton's full steps run off, as from a shape remeshed "
           "under load or a buckled wall.";
  return "Advice: a pressure ends at a rim that is free to move, so an energy minimisation cannot "
         "be offered; hold that rim (the fix op; in the window: Plan > Fix ends), then solve as "
         "an energy minimisation (\"minimize\": true).";
}

std::unique_ptr<engine::ShellModel> make_model(const std::string& name) {
  if (name == "corotational") return engine::make_corotational_shell();
  if (name == "discrete") return engine::make_discrete_shell();
  throw std::invalid_argument("unknown shell model '" + name + "' (corotational, discrete)");
}

std::unique_ptr<engine::ShellModel> state_model_of(const SceneObject& obj) {
  // state_model holds the engine's name of the model (ShellModel::name()).
  for (const char* name : {"corotational", "discrete"}) {
    std::unique_ptr<engine::ShellModel> model = make_model(name);
    if (obj.sim.state_model.empty() || model->name() == obj.sim.state_model) return model;
  }
  throw std::invalid_argument("'" + obj.name + "' was simulated with an unknown shell model '" +
                              obj.sim.state_model + "'");
}

namespace {

void append_loads(engine::Loads& into, const engine::Loads& from, std::size_t node_offset,
                  std::size_t face_offset, std::size_t num_faces) {
  for (auto l : from.nodal) {
    l.node += node_offset;
    into.nodal.push_back(l);
  }
  for (const auto& p : from.pressures) {
    engine::PressureLoad q;
    q.pressure = p.pressure;
    if (p.faces.empty()) {
      for (std::size_t f = 0; f < num_faces; ++f) q.faces.emplace_back(face_offset + f);
    } else {
      for (auto f : p.faces) q.faces.emplace_back(face_offset + f.index());
    }
    into.pressures.push_back(std::move(q));
  }
}

}  // namespace

MergedSystem::MergedSystem(const std::vector<SceneObject*>& objects,
                           const engine::ShellModel& model, const engine::ContactParams* contact,
                           const engine::AreaBarrierParams* barrier)
    : objects_(objects) {
  if (objects.empty()) throw std::invalid_argument("nothing to simulate: no objects");
  std::size_t nodes = 0;
  std::vector<engine::ContactSurface> surfaces;
  // A body force is per object, but the merged system has one Loads::body_force_per_area:
  // each object's body force is converted to nodal loads on its own rest areas instead.
  for (SceneObject* o : objects) {
    node_offset_.push_back(nodes);
    const std::size_t face_offset = faces_.size();
    engine::ContactSurface& surface = surfaces.emplace_back();
    for (std::size_t f = 0; f < o->mesh.num_faces(); ++f) surface.faces.emplace_back(face_offset + f);
    const auto mat_offset = static_cast<int>(materials_.size());
    for (const auto& f : o->mesh.faces())
      faces_.push_back({f[0] + static_cast<int>(nodes), f[1] + static_cast<int>(nodes),
                        f[2] + static_cast<int>(nodes)});
    rest_.elements.insert(rest_.elements.end(), o->sim.rest.elements.begin(),
                          o->sim.rest.elements.end());
    materials_.insert(materials_.end(), o->sim.materials.begin(), o->sim.materials.end());
    for (int m : o->sim.face_material) face_material_.push_back(m + mat_offset);
    state_.x.insert(state_.x.end(), o->sim.state.x.begin(), o->sim.state.x.end());
    state_.D.insert(state_.D.end(), o->sim.state.D.begin(), o->sim.state.D.end());

    const std::size_t n = o->mesh.num_vertices();
    system_.constraints.fixed.resize(nodes + n, 0);
    for (std::size_t i = 0; i < o->sim.constraints.fixed.size() && i < n; ++i)
      system_.constraints.fixed[nodes + i] = o->sim.constraints.fixed[i];

    const auto body_to_nodal = [&](const engine::Loads& l, engine::Loads& into) {
      if (l.body_force_per_area.isZero()) return;
      for (std::size_t e = 0; e < o->mesh.num_faces(); ++e) {
        const double area = engine::rest_area(o->sim.rest.elements[e]);
        for (int k = 0; k < 3; ++k)
          into.nodal.push_back({nodes + o->mesh.faces()[e][k], area / 3.0 * l.body_force_per_area,
                                engine::Vec3::Zero()});
      }
    };
    append_loads(system_.fixed_loads, o->sim.applied_loads, nodes, face_offset, o->mesh.num_faces());
    body_to_nodal(o->sim.applied_loads, system_.fixed_loads);
    append_loads(system_.loads, o->sim.pending_loads, nodes, face_offset, o->mesh.num_faces());
    body_to_nodal(o->sim.pending_loads, system_.loads);
    nodes += n;
  }
  const int d = model.dofs_per_node();
  if (d < 6 && (system_.loads.has_moments() || system_.fixed_loads.has_moments()))
    throw std::invalid_argument("model '" + model.name() +
                                "' has no rotational degrees of freedom: moments cannot be applied");
  // A held rotation the model cannot hold would silently turn a clamp into a pin.
  for (std::size_t i = 0; d < 6 && i < objects.size(); ++i) {
    const auto& fixed = objects[i]->sim.constraints.fixed;
    const auto held = std::count_if(fixed.begin(), fixed.end(),
                                    [](engine::DofMask m) { return (m & engine::kRotations) != 0; });
    if (held > 0)
      throw std::invalid_argument(
          "model '" + model.name() + "' has no rotational degrees of freedom, but " +
          std::to_string(held) + (held == 1 ? " vertex" : " vertices") + " of '" + objects[i]->name +
          (held == 1 ? "' is" : "' are") +
          " held in rotation (fix, or constrain with rotations): it would hold them in "
          "translation only, a pinned end instead of a clamped one. Hold their translations "
          "only (\"dofs\": [\"translations\"]), and clamp an edge by holding two rows of nodes, "
          "or use the model 'corotational'");
  }
  system_.model = &model;
  system_.problem.faces = &faces_;
  system_.problem.rest = &rest_;
  system_.problem.materials = &materials_;
  system_.problem.face_material = &face_material_;
  system_.problem.num_nodes = nodes;
  if (contact != nullptr && objects.size() >= 2) {
    contact_ = std::make_unique<engine::ContactTerm>(system_.problem, surfaces, *contact);
    system_.terms.push_back(contact_.get());
  }
  if (barrier != nullptr) {
    barrier_ = std::make_unique<engine::AreaBarrier>(system_.problem, *barrier);
    system_.terms.push_back(barrier_.get());
  }

  velocity_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nodes * d));
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const auto& v = objects[i]->sim.velocity;
    // A velocity left by another model means other DOFs: that object starts at rest.
    if (objects[i]->sim.state_model == model.name() &&
        v.size() == static_cast<Eigen::Index>(objects[i]->mesh.num_vertices() * d))
      velocity_.segment(static_cast<Eigen::Index>(node_offset_[i] * d), v.size()) = v;
  }
}

void MergedSystem::write_back() {
  const int d = system_.dofs_per_node();
  for (std::size_t i = 0; i < objects_.size(); ++i) {
    SceneObject* o = objects_[i];
    const std::size_t n = o->mesh.num_vertices(), off = node_offset_[i];
    std::copy(state_.x.begin() + off, state_.x.begin() + off + n, o->sim.state.x.begin());
    std::copy(state_.D.begin() + off, state_.D.begin() + off + n, o->sim.state.D.begin());
    o->sim.velocity = velocity_.segment(static_cast<Eigen::Index>(off * d),
                                        static_cast<Eigen::Index>(n * d));
    o->sim.state_model = system_.model->name();
    o->mesh.set_positions(o->sim.state.x);
  }
}

engine::RestState MergedSystem::relax_from() const {
  engine::RestState y0;
  y0.elements.reserve(rest_.elements.size());
  for (const SceneObject* o : objects_) {
    const engine::RestState& r = o->sim.relax_from ? *o->sim.relax_from : o->sim.rest;
    y0.elements.insert(y0.elements.end(), r.elements.begin(), r.elements.end());
  }
  return y0;
}

std::vector<std::pair<std::string, std::span<const engine::Vec3>>> MergedSystem::positions_by_object(
    const std::vector<engine::Vec3>& x) const {
  std::vector<std::pair<std::string, std::span<const engine::Vec3>>> out;
  for (std::size_t i = 0; i < objects_.size(); ++i)
    out.emplace_back(objects_[i]->name,
                     std::span<const engine::Vec3>(x).subspan(node_offset_[i],
                                                              objects_[i]->mesh.num_vertices()));
  return out;
}

bool loads_have_potential(const Workspace& workspace, const std::vector<std::string>& objects) {
  std::vector<SceneObject> copies;
  if (objects.empty()) {
    for (const SceneObject& o : workspace.objects()) copies.push_back(o);
  } else {
    for (const std::string& name : objects) {
      const SceneObject* o = workspace.find(name);
      if (o == nullptr) throw std::invalid_argument("no object named '" + name + "'");
      copies.push_back(*o);
    }
  }
  if (copies.empty()) return true;
  std::vector<SceneObject*> pointers;
  for (SceneObject& o : copies) pointers.push_back(&o);
  const std::unique_ptr<engine::ShellModel> model = make_model("corotational");  // rims need no model
  return free_pressure_rims(MergedSystem(pointers, *model)).empty();
}

std::set<std::size_t> free_pressure_rims(const MergedSystem& merged) {
  const engine::ShellSystem& sys = merged.system();
  std::set<std::size_t> rim;
  for (const engine::Loads* loads : {&sys.loads, &sys.fixed_loads})
    for (const std::size_t v : engine::free_pressure_rim(sys.problem, *loads, sys.constraints)) rim.insert(v);
  return rim;
}

bool restrained(const SceneObject& object) {
  return engine::free_rigid_motions(object.sim.state.x, object.sim.constraints).empty();
}

}  // namespace sutura::app
