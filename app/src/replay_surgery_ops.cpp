// Execution of the surgery ops (incise, join, patch, resect, measure) and of undo/redo.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <tuple>
#include <unordered_set>

#include <Eigen/Dense>

#include "replay_run.hpp"
#include "sutura/app/report.hpp"
#include "sutura/app/section.hpp"
#include "sutura/engine/surgery/surface_attributes.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/measure/cross_section.hpp"
#include "sutura/engine/measure/centreline.hpp"
#include "sutura/engine/measure/lumen_profile.hpp"
#include "sutura/engine/surgery/incise.hpp"
#include "sutura/engine/surgery/join.hpp"
#include "sutura/engine/surgery/patch_plan.hpp"
#include "sutura/engine/surgery/resect.hpp"
#include "sutura/engine/surgery/seam_match.hpp"

namespace sutura::app::detail {

namespace {

// Vertices a remesh must keep where they are: any fixed DOF, a nodal load (applied or pending).
std::vector<bool> kept_vertices(const SceneObject& obj) {
  std::vector<bool> keep(obj.mesh.num_vertices(), false);
  for (std::size_t v = 0; v < keep.size(); ++v)
    for (int dof = 0; dof < 6; ++dof) keep[v] = keep[v] || obj.sim.constraints.is_fixed(v, dof);
  for (const engine::Loads* l : {&obj.sim.applied_loads, &obj.sim.pending_loads})
    for (const auto& n : l->nodal)
      if (n.node < keep.size()) keep[n.node] = true;
  return keep;
}

// Edges a remesh must keep as polylines: earlier sutures and material borders (a patch's rim).
std::vector<std::pair<engine::VertexId, engine::VertexId>> feature_edges(const SceneObject& obj) {
  auto edges = engine::chain_edges(obj.mesh, obj.sim.marks.sutures);
  const auto borders = engine::value_border_edges(obj.mesh, obj.sim.face_material);
  edges.insert(edges.end(), borders.begin(), borders.end());
  return edges;
}

// Remeshes obj with `p`, its features and held vertices added to p's constraints, and carries
// everything across. Returns the report of the remeshed region; `maps` (when given) receives
// the edit's maps.
json remesh_object(SceneObject& obj, engine::RemeshParams p, engine::EditMaps* maps = nullptr) {
  const auto features = feature_edges(obj);
  p.constrained_edges.insert(p.constrained_edges.end(), features.begin(), features.end());
  const std::vector<bool> kept = kept_vertices(obj);
  if (p.constrained_vertices.empty()) p.constrained_vertices.assign(kept.size(), false);
  for (std::size_t v = 0; v < kept.size(); ++v) p.constrained_vertices[v] = p.constrained_vertices[v] || kept[v];
  engine::RemeshResult r = engine::remesh(obj.mesh, p);
  engine::apply_edit(obj.mesh, obj.sim, r.mesh, r.maps);
  if (maps) *maps = std::move(r.maps);
  return {{"target_edge_length_mm", p.target_edge_length},
          {"before", mesh_quality_json(r.before)},
          {"after", mesh_quality_json(r.after)}};
}

// Faces whose current shape is far from their rest shape: stretched or shortened by a factor
// of more than 2 in some direction, or sheared (principal stretches differing by more than
// kShear: a 30-degree triangle made in that shape can be 21 degrees at rest). A patch
// laid compressed into a closed slit is both. A seam remesh leaves them as they are
// (engine::ResampleChainsParams::frozen_faces). The principal stretches squared are the
// eigenvalues of G0^-1 G, G0 and G the Gram matrices of two edges at rest and now.
std::vector<bool> distorted_faces(const SceneObject& obj) {
  constexpr double kFactor = 2.0, kShear = 1.5;
  std::vector<bool> out(obj.mesh.num_faces(), false);
  const auto& faces = obj.mesh.faces();
  const auto& x = obj.mesh.positions();
  for (std::size_t f = 0; f < faces.size() && f < obj.sim.rest.elements.size(); ++f) {
    const auto& X = obj.sim.rest.elements[f].X;
    const engine::Vec3 a0 = X[1] - X[0], b0 = X[2] - X[0];
    const engine::Vec3 a = x[std::size_t(faces[f][1])] - x[std::size_t(faces[f][0])];
    const engine::Vec3 b = x[std::size_t(faces[f][2])] - x[std::size_t(faces[f][0])];
    Eigen::Matrix2d G0, G;
    G0 << a0.dot(a0), a0.dot(b0), a0.dot(b0), b0.dot(b0);
    G << a.dot(a), a.dot(b), a.dot(b), b.dot(b);
    const double det0 = G0.determinant();
    if (!(det0 > 0.0)) { out[f] = true; continue; }
    const Eigen::Matrix2d C = G0.inverse() * G;  // similar to a symmetric matrix: real eigenvalues
    const double tr = C.trace(), det = C.determinant();
    const double disc = std::sqrt(std::max(0.0, 0.25 * tr * tr - det));
    const double hi = 0.5 * tr + disc, lo = 0.5 * tr - disc;  // principal stretches squared
    out[f] = !(lo > 0.0) || hi > kFactor * kFactor || lo < 1.0 / (kFactor * kFactor) || hi > kShear * kShear * lo;
  }
  return out;
}

// Constraints of a seam resampling: the object's held vertices, feature lines and distorted
// faces, and the rest lengths by which a distorted face's seam edges are spaced, added to the
// op's settings `base`.
engine::ResampleChainsParams seam_params(const SceneObject& obj, double target_edge_length,
                                         engine::ResampleChainsParams p) {
  p.target_edge_length = target_edge_length;
  p.constrained_vertices = kept_vertices(obj);
  p.constrained_edges = feature_edges(obj);
  p.frozen_faces = distorted_faces(obj);
  const auto& elements = obj.sim.rest.elements;
  if (elements.size() == obj.mesh.num_faces()) {
    p.rest_edge_lengths.reserve(elements.size());
    for (const auto& e : elements)
      p.rest_edge_lengths.push_back({(e.X[0] - e.X[1]).norm(), (e.X[1] - e.X[2]).norm(), (e.X[2] - e.X[0]).norm()});
  }
  return p;
}

json resample_json(const engine::ResampleChainsResult& r, double spacing) {
  return {{"seam_spacing_mm", spacing},
          {"before", mesh_quality_json(r.before)},
          {"after", mesh_quality_json(r.after)}};
}

// Matches the seams of `pairs` on obj (engine::match_seams) and carries everything across;
// the pairs come back as chains of the new mesh.
json match_object_seams(SceneObject& obj, std::vector<engine::SuturePair>& pairs,
                        const engine::ResampleChainsParams& base) {
  const engine::MatchedSeams m = engine::match_seams(obj.mesh, pairs, seam_params(obj, 0.0, base));
  engine::apply_edit(obj.mesh, obj.sim, m.edit.mesh, m.edit.maps);
  pairs = m.pairs;
  return resample_json(m.edit, *std::min_element(m.spacing.begin(), m.spacing.end()));
}

// Undo depth, whatever the memory: a GUI's history need not be longer.
constexpr std::size_t kMaxUndo = 64;

// An incision whose remeshed band keeps a smaller angle (degrees) gets a warning: the limit
// docs/remeshing.md holds the remeshed meshes to.
constexpr double kThinBandDeg = 20.0;

// The warning for an incision whose band is thin (empty when it is not), with its cause: a
// corner below the limit where the cut meets an open end, which no triangle in it can exceed
// (the drawing forces it), or faces a later `remesh` with `below_angle` can lift (up to that
// corner, when there is one).
std::string thin_band_warning(const engine::IncisionResult& r) {
  if (!r.remeshed || !(r.band_after.min_angle_deg < kThinBandDeg)) return {};
  std::ostringstream w;
  w << std::fixed << std::setprecision(1);
  const std::optional<double> corner = r.open_end_corner_deg;
  const bool sharp_corner = corner && *corner < kThinBandDeg;
  const bool only_the_corner = sharp_corner && r.band_after.min_angle_deg >= *corner - 1e-6;
  if (!only_the_corner)
    w << "the band around the cut keeps an angle of " << r.band_after.min_angle_deg << " degrees (below "
      << kThinBandDeg << "); a remesh with below_angle can lift it" << (sharp_corner ? ", up to the corner below" : "")
      << (sharp_corner ? "; " : "");
  if (sharp_corner)
    w << "the cut meets the open end at " << *corner
      << " degrees: the triangle in that corner can have no larger angle while the lips follow the drawn "
         "curve; draw the cut onto the open end more steeply, or end it before";
  return w.str();
}

// A suture whose one side is longer than this many times the other gets a warning.
constexpr double kUnevenSutureRatio = 2.0;

json suture_report(const engine::SutureReport& s) {
  json j = {{"vertices_a", s.vertices_a},   {"vertices_b", s.vertices_b},
            {"inserted_a", s.inserted_a},   {"inserted_b", s.inserted_b},
            {"length_a_mm", s.length_a},    {"length_b_mm", s.length_b},
            {"max_gap_mm", s.max_gap}};
  if (s.inserted_a + s.inserted_b > 0) {
    std::ostringstream note;
    const bool a = s.inserted_a > 0;
    note << "chain " << (a ? "a" : "b") << " refined: " << (a ? s.inserted_a : s.inserted_b)
         << " vertices inserted (" << (a ? s.vertices_a : s.vertices_b) << " -> "
         << (a ? s.vertices_a + s.inserted_a : s.vertices_b + s.inserted_b)
         << ") to pair with the " << (a ? s.vertices_b : s.vertices_a)
         << " vertices of the other chain by arc length";
    j["resampled"] = note.str();
  }
  return j;
}

json section_json(const engine::CrossSection& c) {
  return {{"closed", c.closed},
          {"area_mm2", c.area},
          {"perimeter_mm", c.perimeter},
          {"equivalent_diameter_mm", c.equivalent_diameter},
          {"min_diameter_mm", c.min_diameter},
          {"max_diameter_mm", c.max_diameter},
          {"centroid", {c.centroid.x(), c.centroid.y(), c.centroid.z()}}};
}

// Rotates a closed chain so that it starts at its vertex farthest along `u` from `centre`.
engine::BoundaryChain start_towards(const engine::SurfaceMesh& mesh, engine::BoundaryChain c,
                                    const engine::Vec3& centre, const engine::Vec3& u) {
  std::size_t best = 0;
  double far = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.vertices.size(); ++i) {
    const double d = (mesh.position(c.vertices[i]) - centre).dot(u);
    if (d > far) far = d, best = i;
  }
  std::rotate(c.vertices.begin(), c.vertices.begin() + std::ptrdiff_t(best), c.vertices.end());
  return c;
}

json mesh_counts(const SceneObject& obj) {
  return {{"vertices", obj.mesh.num_vertices()},
          {"faces", obj.mesh.num_faces()},
          {"boundary_loops", obj.mesh.boundary_loops().size()}};
}

}  // namespace

void Run::remember() {
  ++remembered;
  redo_stack.clear();
  undo_stack.push_back(workspace);  // shares every object until the op edits one
}

void Run::trim_history() {
  // Memory of the history: objects of the undo states that neither the current workspace
  // nor a redo state holds, each counted once (states share the objects that did not change
  // between them). Undo and redo only move states between the stacks, so this grows only
  // with a change, and the redo states, earlier undo states or the workspace itself, stay
  // within what the budget allowed.
  const auto held = [&] {
    std::unordered_set<const SceneObject*> seen;
    for (const auto& o : workspace.objects()) seen.insert(&o);
    for (const Workspace& w : redo_stack)
      for (const auto& o : w.objects()) seen.insert(&o);
    std::size_t bytes = 0;
    for (const Workspace& w : undo_stack)
      for (const auto& o : w.objects())
        if (seen.insert(&o).second) bytes += object_bytes(o);
    return bytes;
  };
  const std::size_t budget = options.limits.undo_megabytes << 20;
  while (!undo_stack.empty() && (undo_stack.size() > kMaxUndo || held() > budget)) {
    undo_stack.erase(undo_stack.begin());
    ++undo_dropped;
  }
}

json Run::execute(const UndoOp&) {
  if (undo_stack.empty())
    throw std::runtime_error(undo_dropped == 0 ? "nothing to undo"
                                               : "nothing more to undo: the history keeps at most " +
                                                     std::to_string(kMaxUndo) + " states and " +
                                                     std::to_string(options.limits.undo_megabytes) +
                                                     " MiB (--max-undo-mb raises it)");
  redo_stack.push_back(std::move(workspace));
  workspace = std::move(undo_stack.back());
  undo_stack.pop_back();
  if (plan.applied > 0) --plan.applied;
  return {{"undo_left", undo_stack.size()}, {"redo_left", redo_stack.size()}};
}

json Run::execute(const RedoOp&) {
  if (redo_stack.empty()) throw std::runtime_error("nothing to redo");
  undo_stack.push_back(std::move(workspace));
  workspace = std::move(redo_stack.back());
  redo_stack.pop_back();
  if (plan.applied < plan.steps.size()) ++plan.applied;
  return {{"undo_left", undo_stack.size()}, {"redo_left", redo_stack.size()}};
}

json Run::execute(const InciseOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  engine::IncisionParams params = op.params;
  if (params.remesh) {
    params.constrained_vertices = kept_vertices(obj);
    params.constrained_edges = feature_edges(obj);
  }
  const engine::IncisionResult r = engine::incise(obj.mesh, op.points, params);
  engine::apply_edit(obj.mesh, obj.sim, r.mesh, r.maps);
  obj.sim.marks.incisions.push_back(r.left);
  obj.sim.marks.incisions.push_back(r.right);
  json j = {{"object", op.object},
            {"mode", op.params.mode == engine::IncisionMode::SnapToEdges ? "snap" : "cut"},
            {"length_mm", r.length},
            {"lip_vertices", r.left.size()},
            {"inserted_vertices", r.inserted_vertices},
            {"snapped_points", r.snapped_points},
            {"starts_on_boundary", r.starts_on_boundary},
            {"ends_on_boundary", r.ends_on_boundary}};
  if (r.remeshed) j["remesh"] = {{"before", mesh_quality_json(r.band_before)}, {"after", mesh_quality_json(r.band_after)}};
  if (r.band_repair_fraction > 0.0) j["remesh"]["repaired_at"] = r.band_repair_fraction;
  if (r.open_end_corner_deg) j["open_end_corner_deg"] = *r.open_end_corner_deg;
  if (const std::string w = thin_band_warning(r); !w.empty()) j["warning"] = w;
  j["mesh"] = mesh_counts(obj);
  return j;
}

json Run::execute(const JoinOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  std::vector<engine::SuturePair> pairs;
  for (std::size_t i = 0; i < op.sutures.size(); ++i) {
    try {
      pairs.push_back({engine::find_boundary_chain(obj.mesh, op.sutures[i].a),
                       engine::find_boundary_chain(obj.mesh, op.sutures[i].b)});
    } catch (const engine::InvalidArgument& e) {
      throw std::runtime_error("suture " + std::to_string(i + 1) + ": " + e.what());
    }
  }
  json seams;
  if (op.remesh) seams = match_object_seams(obj, pairs, op.seams);
  engine::JoinParams params = op.join;
  if (op.remesh) params.pairing = engine::JoinPairing::InOrder;  // matched: one to one
  if (params.placement == engine::SuturePlacement::OntoB) {
    params.held.assign(obj.mesh.num_vertices(), false);
    for (std::size_t v = 0; v < params.held.size(); ++v)
      for (int dof = 0; dof < 3; ++dof)
        if (obj.sim.constraints.is_fixed(v, dof)) params.held[v] = true;
  }
  const engine::JoinResult r = engine::join(obj.mesh, pairs, params);
  engine::apply_edit(obj.mesh, obj.sim, r.mesh, r.maps);
  std::vector<bool> moved_faces;
  if (params.placement != engine::SuturePlacement::Mean) {
    // The placement moved the copies and the vertices around them away from their carried
    // (mean) positions: the state starts where the join put it, and every face it moved
    // starts congruent (y0), so the joined shape is stress-free before the relaxation.
    obj.sim.state.x = r.mesh.positions();
    obj.mesh.set_positions(obj.sim.state.x);
    moved_faces.assign(obj.mesh.num_faces(), false);
    for (const auto v : r.displaced)
      for (const auto f : obj.mesh.vertex_faces(v)) moved_faces[f.index()] = true;
  }
  engine::start_relaxation(obj.mesh, obj.sim, r.merged, moved_faces);
  for (const auto& seam : r.seams) obj.sim.marks.sutures.push_back(seam);
  json sutures = json::array();
  std::string uneven;
  for (std::size_t i = 0; i < r.sutures.size(); ++i) {
    const engine::SutureReport& s = r.sutures[i];
    sutures.push_back(suture_report(s));
    // Sides of very different length: the shorter is stretched along the longer (a chain
    // picked too short or too long, or the wrong lip), which a surgeon would not sew.
    const double shorter = std::min(s.length_a, s.length_b), longer = std::max(s.length_a, s.length_b);
    if (longer > kUnevenSutureRatio * shorter) {
      std::ostringstream w;
      w << (uneven.empty() ? "" : "; ") << "suture " << i + 1 << ": its sides differ in length by a factor of "
        << std::setprecision(2) << std::fixed << longer / shorter << " (" << s.length_a << " mm against "
        << s.length_b << " mm), more than " << kUnevenSutureRatio
        << ": the shorter side is stretched along the longer; check the chains picked";
      uneven += w.str();
    }
  }
  json j = {{"object", op.object},
            {"sutures", sutures},
            {"merged_vertices", r.merged.size()},
            {"displaced_vertices", r.displaced.size()}};
  if (!uneven.empty()) j["warning"] = uneven;
  if (!seams.is_null()) j["remesh"] = seams;
  j["mesh"] = mesh_counts(obj);
  return j;
}

json Run::execute(const PatchOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  using SeamRemesh = PatchOp::SeamRemesh;
  engine::PatchPlanParams params = op.params;
  params.max_faces = double(options.limits.faces_per_object);
  json remeshed;
  if (op.remesh == SeamRemesh::Matched) {
    // Each lip and the patch edge sutured to it get one count of equal segments at the
    // patch's spacing: the lips are resampled here, the edges by plan_patch (flat, in the
    // patch's rest shape), and the join pairs them one to one.
    const engine::PatchPlan first = engine::plan_patch(obj.mesh, op.start, op.end, params);
    auto segments = [&](const engine::BoundaryChain& lip, const engine::BoundaryChain& edge) {
      const double mean =
          0.5 * (engine::chain_length(obj.mesh, lip) + engine::chain_length(first.rest, edge));
      return static_cast<int>(std::max(1L, std::lround(mean / first.edge_length)));
    };
    params.left_segments = segments(first.lip_left, first.edge_left);
    params.right_segments = segments(first.lip_right, first.edge_right);
    // The lips' band is graded from the patch's spacing to the host's (a patch is cut no
    // finer than a fifth of its width, a fine host is finer than that).
    engine::ResampleChainsParams rp = seam_params(obj, first.edge_length, op.seams);
    rp.grading = 1.5;
    const engine::ResampleChainsResult r = engine::resample_chains(
        obj.mesh,
        {{first.lip_left, engine::equal_fractions(params.left_segments)},
         {first.lip_right, engine::equal_fractions(params.right_segments)}},
        rp);
    engine::apply_edit(obj.mesh, obj.sim, r.mesh, r.maps);
    remeshed = resample_json(r, first.edge_length);
  }
  const engine::PatchPlan plan = engine::plan_patch(obj.mesh, op.start, op.end, params);
  const std::size_t host_faces = obj.mesh.num_faces();
  const std::size_t offset = engine::append_component(obj.mesh, obj.sim, plan.placed, plan.rest, op.material);
  // append_component gave the patch a material of its own, the last (the plan report names
  // patches by it).
  const int material_index = static_cast<int>(obj.sim.materials.size()) - 1;
  auto shifted = [&](engine::BoundaryChain c) {
    for (auto& v : c.vertices) v = engine::VertexId(v.index() + offset);
    return c;
  };
  engine::JoinParams join_params = op.join;
  if (plan.matched) join_params.pairing = engine::JoinPairing::InOrder;
  const engine::JoinResult r =
      engine::join(obj.mesh, {{plan.lip_left, shifted(plan.edge_left)},
                              {plan.lip_right, shifted(plan.edge_right)}}, join_params);
  // The whole patch starts congruent with its placement (it is laid out curved, cut flat).
  std::vector<bool> patch_faces(r.mesh.num_faces(), false);
  for (std::size_t f = 0; f < r.maps.faces.size(); ++f)
    patch_faces[f] = r.maps.faces[f].parent.index() >= host_faces;
  engine::apply_edit(obj.mesh, obj.sim, r.mesh, r.maps);
  engine::start_relaxation(obj.mesh, obj.sim, r.merged, patch_faces);
  for (const auto& seam : r.seams) obj.sim.marks.sutures.push_back(seam);
  if (op.remesh == SeamRemesh::HostAfterJoin) {
    // Format 2: the host's side of the seams, after the join, where the pairing inserted
    // vertices along the lips. The patch's own faces are kept: laid out narrow over the slit,
    // far from their flat rest shape, their strain varies too fast across the band to be
    // resampled (docs/remeshing.md).
    const int patch_material = static_cast<int>(obj.sim.materials.size()) - 1;
    engine::RemeshParams p = engine::band_around(obj.mesh, r.seams, 2.0);
    p.passes = op.params.seam_passes;
    std::erase_if(*p.region, [&](engine::FaceId f) {
      return obj.sim.face_material[f.index()] == patch_material;
    });
    remeshed = remesh_object(obj, std::move(p));
  }
  json sutures = json::array();
  for (const auto& s : r.sutures) sutures.push_back(suture_report(s));
  json j = {{"object", op.object},
            {"incision_length_mm", plan.incision_length},
            {"patch_vertices", plan.rest.num_vertices()},
            {"patch_faces", plan.rest.num_faces()},
            {"patch_area_mm2", plan.rest.total_area()},
            {"material_index", material_index},
            {"sutures", sutures}};
  if (!remeshed.is_null()) j["remesh"] = remeshed;
  j["mesh"] = mesh_counts(obj);
  if (const std::string w = engine::material_warning(op.material); !w.empty()) j["warning"] = "patch material: " + w;
  return j;
}

json Run::execute(const ResectOp& op) {
  remember();
  SceneObject& obj = edit(op.object);
  engine::Vec3 seed = engine::Vec3::Zero();
  if (op.seed) {
    seed = *op.seed;
  } else {
    for (const auto& p : op.planes) seed += p.origin;
    seed /= double(op.planes.size());
  }
  const engine::ResectionResult rr = engine::resect(obj.mesh, op.planes, seed, op.params);
  engine::apply_edit(obj.mesh, obj.sim, rr.mesh, rr.maps);
  json j = {{"object", op.object},
            {"removed_faces", rr.removed_faces},
            {"removed_area_mm2", rr.removed_area}};
  std::vector<engine::BoundaryChain> cut_loops = rr.loops;
  if (op.remesh) {
    // The band around the cut: its first vertex per loop held, to find the loop again.
    std::vector<std::vector<engine::VertexId>> lines;
    for (const auto& l : cut_loops) lines.push_back(l.vertices);
    engine::RemeshParams p = engine::band_around(obj.mesh, lines, 2.0);
    p.passes = op.seams.band_passes;
    p.constrained_vertices.assign(obj.mesh.num_vertices(), false);
    for (const auto& l : cut_loops) p.constrained_vertices[l.vertices.front().index()] = true;
    engine::EditMaps maps;
    const std::size_t old_vertices = obj.mesh.num_vertices();
    j["remesh"] = remesh_object(obj, std::move(p), &maps);
    std::vector<engine::VertexId> image(old_vertices);
    for (std::size_t v = 0; v < maps.vertices.size(); ++v)
      if (maps.vertices[v].kind == engine::VertexOriginKind::Copy)
        image[maps.vertices[v].parents[0].index()] = engine::VertexId(v);
    for (auto& l : cut_loops) {
      const engine::VertexId first = image[l.vertices.front().index()];
      l = l.closed ? engine::boundary_chain(obj.mesh, first, first)
                   : engine::boundary_chain(obj.mesh, first, image[l.vertices.back().index()]);
    }
  }
  json loops = json::array();
  for (const auto& l : cut_loops) loops.push_back(l.vertices.size());
  j["loop_vertices"] = loops;
  if (op.anastomosis) {
    const engine::Vec3 ca = loop_centroid(obj.mesh, cut_loops[0].vertices),
                       cb = loop_centroid(obj.mesh, cut_loops[1].vertices);
    // Start both loops on the same side so the ends are sutured without a twist.
    engine::Vec3 axis = cb - ca;
    if (axis.norm() < 1e-12) axis = op.planes[0].normal;
    axis.normalize();
    engine::Vec3 u = op.align ? engine::Vec3(*op.align - ca) : engine::Vec3::UnitX();
    u -= u.dot(axis) * axis;
    if (u.norm() < 1e-9) u = axis.unitOrthogonal();
    u.normalize();
    std::vector<engine::SuturePair> pairs = {{start_towards(obj.mesh, cut_loops[0], ca, u),
                                              start_towards(obj.mesh, cut_loops[1], cb, u)}};
    engine::JoinParams params = op.join;
    if (op.remesh) {
      j["seam_remesh"] = match_object_seams(obj, pairs, op.seams);
      params.pairing = engine::JoinPairing::InOrder;  // matched: one to one
    }
    const engine::JoinResult r = engine::join(obj.mesh, pairs, params);
    engine::apply_edit(obj.mesh, obj.sim, r.mesh, r.maps);
    engine::start_relaxation(obj.mesh, obj.sim, r.merged, {});
    for (const auto& seam : r.seams) obj.sim.marks.sutures.push_back(seam);
    j["anastomosis"] = suture_report(r.sutures[0]);
  }
  j["mesh"] = mesh_counts(obj);
  return j;
}

json Run::execute(const RemeshOp& op) {
  engine::RemeshParams p;
  const engine::SurfaceMesh& mesh = object(op.object).mesh;
  if (!op.near.empty()) {
    p.region = engine::faces_near_polyline(mesh, op.near, op.radius);
    if (p.region->empty())
      throw std::runtime_error("near: no face of '" + op.object + "' has a corner within " +
                               std::to_string(op.radius) + " mm of the points");
  }
  if (op.below_angle > 0.0) {
    p.region = engine::faces_near_small_angles(mesh, op.below_angle, op.radius);
    if (p.region->empty()) {  // nothing to do: the object and the history stay as they are
      const engine::MeshQuality q = engine::mesh_quality(mesh);
      std::ostringstream m;
      m << std::fixed << std::setprecision(1) << "no face of '" << op.object << "' has an angle below "
        << op.below_angle << " degrees (smallest " << q.min_angle_deg << "): unchanged";
      return {{"object", op.object}, {"below_angle_deg", op.below_angle}, {"faces", 0},
              {"min_angle_deg", q.min_angle_deg}, {"mesh", mesh_counts(object(op.object))}, {"summary", m.str()}};
    }
  }
  p.target_edge_length = op.target_edge_length > 0.0
                             ? op.target_edge_length
                             : engine::mean_edge_length(mesh, p.region.value_or(std::vector<engine::FaceId>{}));
  remember();
  SceneObject& obj = edit(op.object);
  p.grading = op.grading;
  if (op.grading > 1.0) p.grading_curve = op.near;
  p.passes = op.passes;
  json j = remesh_object(obj, std::move(p));
  j["object"] = op.object;
  if (op.below_angle > 0.0) {
    j["below_angle_deg"] = op.below_angle;
    std::ostringstream m;
    m << std::fixed << std::setprecision(1) << "remeshed " << j["before"]["faces"].get<std::size_t>()
      << " faces of '" << op.object << "' around angles below " << op.below_angle
      << " degrees: smallest angle there " << j["before"]["min_angle_deg"].get<double>() << " -> "
      << j["after"]["min_angle_deg"].get<double>() << " degrees";
    j["summary"] = m.str();
  }
  j["mesh"] = mesh_counts(obj);
  return j;
}

json Run::execute(const DistanceOp& op) {
  const engine::HausdorffDistance h =
      engine::hausdorff_distance(object(op.a).mesh, object(op.b).mesh, op.spacing);
  json j = hausdorff_json(h);
  j["a"] = op.a;
  j["b"] = op.b;
  measurements[op.name] = j;
  return {{"measurement", op.name}, {"values", j}};
}

namespace {

// The automatic centreline of `mesh` between the tree points nearest op.from and op.to, as a
// polyline, and its length (mm); when op.stations is 0, sets one station per mean edge length
// (at least 20). `from` and `to` must lie within three radii of the tree (near the vessel).
std::pair<std::vector<engine::Vec3>, double> auto_centreline_path(const MeasureOp& op, const engine::SurfaceMesh& mesh,
                                                                  const char* side_name, engine::LumenProfileParams& p) {
  const std::string where = "measure '" + op.name + "' (" + side_name + ", object '" + op.object + "'): ";
  engine::CentrelineTree tree;
  try {
    tree = engine::extract_centreline(mesh);
  } catch (const engine::InvalidArgument& e) {
    throw std::runtime_error(where + e.what());
  }
  for (const auto& [field, point] : {std::pair{"from", op.from}, std::pair{"to", op.to}}) {
    const auto nearest = static_cast<std::size_t>(engine::nearest_centreline_point(tree, point));
    const double d = (tree.points[nearest] - point).norm();
    if (d > 3.0 * tree.radii[nearest]) {
      std::ostringstream m;
      m << where << "'" << field << "' is " << std::fixed << std::setprecision(2) << d
        << " mm from the vessel's centreline, more than three lumen radii (" << 3.0 * tree.radii[nearest]
        << " mm); give a point in or near the vessel";
      throw std::runtime_error(m.str());
    }
  }
  std::vector<engine::Vec3> path;
  try {
    path = engine::centreline_path(tree, op.from, op.to);
  } catch (const engine::InvalidArgument& e) {
    throw std::runtime_error(where + e.what());
  }
  double length = 0.0;
  for (std::size_t k = 1; k < path.size(); ++k) length += (path[k] - path[k - 1]).norm();
  if (p.stations == 0) {
    const double edge = engine::mean_edge_length(mesh, {});
    p.stations = static_cast<int>(std::clamp(std::round(length / edge), 20.0, 10000.0));
  }
  return {std::move(path), length};
}

}  // namespace

json Run::execute(const MeasureOp& op) {
  const SceneObject& obj = object(op.object);
  json j = {{"object", op.object}};
  const double radius = op.max_radius > 0 ? op.max_radius : std::numeric_limits<double>::infinity();
  if (op.plane) {
    const auto [before, after] = measure_section(obj, *op.plane, op.max_radius);
    j["before"] = section_json(before);
    j["after"] = section_json(after);
    j["area_change_percent"] = 100.0 * (after.area - before.area) / before.area;
    std::ostringstream m;
    m << std::fixed << std::setprecision(2) << "cross-section area " << before.area
      << " mm2 in the pre-operative shape -> " << after.area << " mm2 now ("
      << std::showpos << std::setprecision(1) << j["area_change_percent"].get<double>()
      << std::noshowpos << " %), equivalent diameter " << std::setprecision(2)
      << before.equivalent_diameter << " -> " << after.equivalent_diameter << " mm";
    j["summary"] = m.str();
  } else {
    for (const auto* which : {&obj.before, &obj.mesh}) {
      const char* side_name = which == &obj.before ? "before" : "after";
      std::vector<engine::Vec3> line = op.centreline;
      engine::LumenProfileParams p;
      p.stations = op.stations;
      p.max_radius = radius;
      json side;
      if (op.auto_centreline) {
        double length = 0.0;
        std::tie(line, length) = auto_centreline_path(op, *which, side_name, p);
        side["centreline_length_mm"] = length;
      }
      const engine::LumenProfile prof = engine::lumen_profile(*which, line, p);
      json stations = json::array();
      for (const auto& s : prof.stations)
        stations.push_back({{"arc_length_mm", s.arc_length},
                            {"area_mm2", s.section ? json(s.section->area) : json(nullptr)},
                            {"closed", s.section ? s.section->closed : false}});
      side["stations"] = stations;
      if (!prof.min_area_station)
        throw std::runtime_error("measure '" + op.name + "': no closed cross-section along the "
                                 "centreline of object '" + op.object + "'");
      const auto& m = prof.stations[*prof.min_area_station];
      side["min_area_mm2"] = m.section->area;
      side["min_area_arc_length_mm"] = m.arc_length;
      side["min_equivalent_diameter_mm"] = m.section->equivalent_diameter;
      side["min_area_point"] = {m.section->centroid.x(), m.section->centroid.y(), m.section->centroid.z()};
      j[side_name] = side;
    }
    const double b = j["before"]["min_area_mm2"].get<double>();
    const double a = j["after"]["min_area_mm2"].get<double>();
    j["min_area_change_percent"] = 100.0 * (a - b) / b;
    std::ostringstream m;
    m << std::fixed << std::setprecision(2) << "minimum lumen area " << b
      << " mm2 in the pre-operative shape -> " << a << " mm2 now (" << std::showpos
      << std::setprecision(1) << j["min_area_change_percent"].get<double>() << std::noshowpos
      << " %), at " << j["after"]["min_area_arc_length_mm"].get<double>()
      << " mm along the centreline";
    if (op.auto_centreline) {
      const auto& c = j["after"]["min_area_point"];
      m << " (" << c[0].get<double>() << ", " << c[1].get<double>() << ", " << c[2].get<double>()
        << "; automatic centreline)";
    }
    j["summary"] = m.str();
  }
  measurements[op.name] = j;
  return {{"measurement", op.name}, {"values", j}};
}

}  // namespace sutura::app::detail
