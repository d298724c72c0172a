#include "sutura/app/limits.hpp"

#include <cmath>
#include <set>
#include <variant>

#include "sutura/app/workspace.hpp"

namespace sutura::app {

namespace {

// 12345678 -> "12,345,678".
std::string count_text(double n) {
  std::string digits = std::to_string(std::llround(n));
  for (int i = int(digits.size()) - 3; i > 0; i -= 3) digits.insert(std::size_t(i), ",");
  return digits;
}

// "<before><amount><after> exceeds the limit of <limit> (<flag> raises it)".
[[noreturn]] void refuse(const Session& s, const Action& a, const std::string& field, const std::string& before,
                         double amount, const std::string& after, double limit, const char* flag) {
  throw SessionError(s.file.string(), a.line, a.name, field,
                     before + count_text(amount) + after + " exceeds the limit of " + count_text(limit) + " (" +
                         flag + " raises it)");
}

// Faces of a generated mesh, as the generator makes them (a patch: about 4 / (sqrt(3) h^2) per
// unit area, its outline's area at most length x width).
double generated_faces(const GenerateOp& op) {
  return std::visit(
      [](const auto& p) -> double {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, engine::TubeParams> || std::is_same_v<P, engine::CylinderPanelParams>)
          return 2.0 * double(p.segments_around) * double(p.segments_along);
        else if constexpr (std::is_same_v<P, engine::StripParams>)
          return 2.0 * double(p.segments_length) * double(p.segments_width);
        else
          return 2.31 * p.length * p.width / (p.target_edge_length * p.target_edge_length);
      },
      op.params);
}

// A patch `width` mm wide: the incision is at least as long as its end points are apart; the
// planner cuts no finer than edge_length when it is given.
void check_patch(const Session& session, const Action& a, const PatchOp& p, double width, const char* field,
                 const Limits& limits) {
  const double h = p.params.edge_length;
  const double length = p.params.length > 0 ? p.params.length : (p.end - p.start).norm();
  if (h > 0) {
    const double faces = 2.31 * length * width / (h * h);
    if (faces > double(limits.faces_per_object))
      refuse(session, a, field, "a patch of about ", faces, " faces", double(limits.faces_per_object),
             "--max-faces");
  }
}

void check_run(const Session& session, const Action& a, const SimulateOp& r, const std::string& prefix,
               const Limits& limits) {
  const double steps = r.relax ? double(r.relax->steps) + double(r.relax->settle_steps) : double(r.params.steps);
  if (steps > double(limits.steps))
    refuse(session, a, prefix + (r.relax ? "relax.steps" : "steps"), "a run of ", steps, " steps",
           double(limits.steps), "--max-steps");
}

}  // namespace

void check_limits(const Session& session, const Limits& limits) {
  std::set<std::string> objects;
  for (const Action& a : session.actions) {
    if (const auto* g = std::get_if<GenerateOp>(&a.op)) {
      const double faces = generated_faces(*g);
      if (faces > double(limits.faces_per_object))
        refuse(session, a, "segments", "a generated mesh of ", faces, " faces", double(limits.faces_per_object),
               "--max-faces");
      objects.insert(g->object);
    } else if (const auto* l = std::get_if<LoadOp>(&a.op)) {
      objects.insert(l->object);
    } else if (const auto* p = std::get_if<PatchOp>(&a.op)) {
      check_patch(session, a, *p, p->params.width, "edge_length", limits);
    } else if (const auto* d = std::get_if<DesignPatchOp>(&a.op)) {
      // Every candidate is a patch and a run: the widest patch, and each run's steps (the
      // number of candidates is bounded by max_relaxations, their time by --time-limit).
      check_patch(session, a, d->patch, d->width_max, "patch.edge_length", limits);
      check_run(session, a, d->simulate, "simulate.", limits);
    } else if (const auto* shot = std::get_if<SnapshotOp>(&a.op)) {
      const double pixels = double(shot->width) * double(shot->height) * (shot->side_by_side ? 2.0 : 1.0);
      if (pixels > double(limits.pixels))
        refuse(session, a, "width", "a snapshot of ", pixels, " pixels", double(limits.pixels), "--max-pixels");
    } else if (const auto* pr = std::get_if<PlanReportOp>(&a.op)) {
      // Each standard view is a snapshot of two halves.
      const double pixels = 2.0 * double(pr->view_width) * double(pr->view_height);
      if (pixels > double(limits.pixels))
        refuse(session, a, "view_width", "a plan report's view of ", pixels, " pixels", double(limits.pixels),
               "--max-pixels");
    } else if (const auto* r = std::get_if<SimulateOp>(&a.op)) {
      check_run(session, a, *r, "", limits);
    }
    if (objects.size() > limits.objects)
      refuse(session, a, "object", "", double(objects.size()), " objects", double(limits.objects), "--max-objects");
  }
}

std::size_t object_bytes(const SceneObject& o) {
  // Per vertex: the mesh, pre-operative and reference positions (and measures, after an
  // unload), the state (position and a triad), velocity, constraints and loads: about 30
  // doubles. Per face: indices in the mesh
  // and the pre-operative mesh, the rest element (3 points and its derived data), material:
  // about 40 doubles. Halfedge connectivity: 3 per face, twins and vertex links.
  return 240 * (o.mesh.num_vertices() + o.before.num_vertices()) +
         400 * (o.mesh.num_faces() + o.before.num_faces());
}

}  // namespace sutura::app
