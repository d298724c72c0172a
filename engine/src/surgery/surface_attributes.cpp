#include "sutura/engine/surgery/surface_attributes.hpp"

#include <algorithm>
#include <map>
#include <string>

#include "sutura/engine/errors.hpp"
#include "sutura/engine/surgery/carry.hpp"
#include "sutura/engine/surgery/relaxation.hpp"

namespace sutura::engine {

namespace {

// New vertex standing for each old vertex: the new vertex with the largest weight on it
// (a copy, a merge containing it, or the nearest inserted point); invalid when removed.
std::vector<VertexId> vertex_images(const EditMaps& maps, std::size_t old_count) {
  std::vector<VertexId> image(old_count);
  std::vector<double> best(old_count, 0.0);
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const auto& o = maps.vertices[v];
    for (std::size_t i = 0; i < o.parents.size(); ++i) {
      const std::size_t p = o.parents[i].index();
      // Strictly greater: the first (lowest new id) wins ties, e.g. the lip that kept the id.
      if (p < old_count && o.weights[i] > best[p]) {
        best[p] = o.weights[i];
        image[p] = VertexId(v);
      }
    }
  }
  return image;
}

Loads carry_loads(const EditMaps& maps, const Loads& old, const std::vector<VertexId>& image) {
  Loads out = old;
  out.nodal.clear();
  for (const auto& n : old.nodal) {
    if (n.node >= image.size() || !image[n.node].valid()) continue;  // removed with its region
    auto moved = n;
    moved.node = image[n.node].index();
    out.nodal.push_back(moved);
  }
  for (auto& p : out.pressures)
    if (!p.faces.empty()) p.faces = carry_face_set(maps, p.faces);
  return out;
}

// New vertices inserted on old edges: (a, b) with a < b -> (weight of b, new vertex), sorted.
using EdgePoints = std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::pair<double, VertexId>>>;

EdgePoints points_on_old_edges(const EditMaps& maps) {
  EdgePoints on;
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    if (o.kind != VertexOriginKind::Interpolated || o.parents.size() != 2) continue;
    const bool swap = o.parents[0].value > o.parents[1].value;
    const auto key = swap ? std::pair{o.parents[1].value, o.parents[0].value}
                          : std::pair{o.parents[0].value, o.parents[1].value};
    on[key].emplace_back(swap ? o.weights[0] : o.weights[1], VertexId(v));
  }
  for (auto& [key, points] : on) std::sort(points.begin(), points.end());
  return on;
}

// A chain follows its vertices (their images) and takes in the vertices an edit inserted on
// its edges, in order; removed vertices drop out.
std::vector<VertexId> carry_chain(const std::vector<VertexId>& chain,
                                  const std::vector<VertexId>& image, const EdgePoints& on) {
  std::vector<VertexId> out;
  auto add = [&](VertexId v) {
    if (v.valid() && (out.empty() || out.back() != v)) out.push_back(v);
  };
  for (std::size_t i = 0; i < chain.size(); ++i) {
    const VertexId v = chain[i];
    if (v.index() < image.size()) add(image[v.index()]);
    if (i + 1 == chain.size()) break;
    const VertexId w = chain[i + 1];
    const bool forward = v.value < w.value;
    const auto it = on.find(forward ? std::pair{v.value, w.value} : std::pair{w.value, v.value});
    if (it == on.end()) continue;
    if (forward)
      for (const auto& p : it->second) add(p.second);
    else
      for (auto p = it->second.rbegin(); p != it->second.rend(); ++p) add(p->second);
  }
  return out;
}

SurfaceMarks carry_marks(const SurfaceMarks& old, const std::vector<VertexId>& image,
                         const EditMaps& maps) {
  SurfaceMarks out;
  if (old.incisions.empty() && old.sutures.empty()) return out;
  const EdgePoints on = points_on_old_edges(maps);
  for (const auto& c : old.incisions)
    if (auto n = carry_chain(c, image, on); n.size() >= 2) out.incisions.push_back(std::move(n));
  for (const auto& c : old.sutures)
    if (auto n = carry_chain(c, image, on); n.size() >= 2) out.sutures.push_back(std::move(n));
  return out;
}

// Per-vertex blocks of `old` (dofs per vertex = size / old_vertex_count) by the vertex weights.
Eigen::VectorXd carry_velocity(const EditMaps& maps, const Eigen::VectorXd& old,
                               std::size_t old_vertex_count) {
  if (old.size() == 0 || old_vertex_count == 0) return {};
  const auto n_old = static_cast<Eigen::Index>(old_vertex_count);
  if (old.size() % n_old != 0) return {};  // not per vertex: at rest after the edit
  const Eigen::Index d = old.size() / n_old;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(maps.vertices.size()) * d);
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const VertexOrigin& o = maps.vertices[v];
    for (std::size_t i = 0; i < o.parents.size(); ++i)
      out.segment(static_cast<Eigen::Index>(v) * d, d) +=
          o.weights[i] * old.segment(static_cast<Eigen::Index>(o.parents[i].index()) * d, d);
  }
  return out;
}

}  // namespace

SurfaceAttributes attributes_at_rest(const SurfaceMesh& mesh) {
  SurfaceAttributes a;
  a.state = state_from_mesh(mesh);
  a.rest = rest_from_state(mesh, a.state);
  a.face_material.assign(mesh.num_faces(), 0);
  a.reference = mesh.positions();
  return a;
}

SurfaceAttributes carry_attributes(const EditMaps& maps, const SurfaceMesh& old_mesh,
                                   const SurfaceAttributes& old,
                                   const std::vector<FaceIndices>& new_faces) {
  const std::size_t old_vertex_count = old_mesh.num_vertices();
  // One binding of every channel: adding a member to SurfaceAttributes breaks this line until
  // the new channel gets its rule below.
  const auto& [state, rest, relax_from, relax_s, materials, face_material, constraints,
               applied_loads, pending_loads, pending_factor, velocity, state_model, reference,
               marks] = old;
  const auto image = vertex_images(maps, old_vertex_count);
  ShellState new_state = carry_state(maps, state);
  const EditGeometry geometry{old_mesh.faces(), state, new_faces, new_state};
  SurfaceAttributes out{
      new_state,
      carry_rest(maps, rest, &geometry),
      relax_from ? std::optional<RestState>(carry_rest(maps, *relax_from, &geometry))
                 : std::nullopt,
      relax_s,
      materials,
      carry_face_values(maps, face_material),
      carry_constraints(maps, constraints),
      carry_loads(maps, applied_loads, image),
      carry_loads(maps, pending_loads, image),
      pending_factor,
      carry_velocity(maps, velocity, old_vertex_count),
      state_model,
      carry_points(maps, reference),
      carry_marks(marks, image, maps),
  };
  return out;
}

void apply_edit(SurfaceMesh& mesh, SurfaceAttributes& attrs, SurfaceMesh edited,
                const EditMaps& maps) {
  if (maps.vertices.size() != edited.num_vertices() || maps.faces.size() != edited.num_faces())
    throw InvalidArgument("apply_edit: the maps do not describe the edited mesh");
  SurfaceAttributes carried = carry_attributes(maps, mesh, attrs, edited.faces());
  edited.set_positions(carried.state.x);
  mesh = std::move(edited);
  attrs = std::move(carried);
}

std::size_t append_component(SurfaceMesh& mesh, SurfaceAttributes& attrs,
                             const SurfaceMesh& placed, const SurfaceMesh& rest_shape,
                             const ShellMaterial& material) {
  if (placed.faces() != rest_shape.faces() || placed.num_vertices() != rest_shape.num_vertices())
    throw InvalidArgument("append_component: the placed part and its rest shape differ in faces");
  const std::size_t offset = mesh.num_vertices();
  const std::size_t face_offset = mesh.num_faces();
  const std::size_t n = placed.num_vertices();
  // One binding of every channel, as in carry_attributes: each gets its union rule.
  auto& [state, rest, relax_from, relax_s, materials, face_material, constraints, applied_loads,
         pending_loads, pending_factor, velocity, state_model, reference, marks] = attrs;
  const RestState part_rest = rest_from_state(rest_shape, state_from_mesh(rest_shape));
  for (const auto& p : placed.positions()) {
    state.x.push_back(p);
    state.D.push_back(Quat::Identity());
    reference.push_back(p);
  }
  rest.elements.insert(rest.elements.end(), part_rest.elements.begin(), part_rest.elements.end());
  if (relax_from)  // the part is at rest: its y0 is its x0
    relax_from->elements.insert(relax_from->elements.end(), part_rest.elements.begin(),
                                part_rest.elements.end());
  (void)relax_s;  // of the existing part; the new part has nothing to relax
  materials.push_back(material);
  face_material.resize(face_offset, 0);
  face_material.resize(face_offset + placed.num_faces(), static_cast<int>(materials.size() - 1));
  if (!constraints.fixed.empty()) constraints.fixed.resize(offset + n, 0);
  // Loads: nodal ones and face lists keep their ids (the old part keeps its numbering);
  // whole-surface pressures and the body force extend to the new part.
  (void)applied_loads;
  (void)pending_loads;
  (void)pending_factor;
  if (velocity.size() > 0 && offset > 0 && velocity.size() % static_cast<Eigen::Index>(offset) == 0) {
    const Eigen::Index d = velocity.size() / static_cast<Eigen::Index>(offset);
    velocity.conservativeResize(static_cast<Eigen::Index>(offset + n) * d);
    velocity.tail(static_cast<Eigen::Index>(n) * d).setZero();  // the part is at rest
  } else {
    velocity.resize(0);
  }
  (void)state_model;
  (void)marks;  // the new part has no marks yet; the old ones keep their ids
  std::vector<Vec3> x = mesh.positions();
  std::vector<FaceIndices> faces = mesh.faces();
  x.insert(x.end(), placed.positions().begin(), placed.positions().end());
  for (auto f : placed.faces()) {
    for (auto& v : f) v += static_cast<int>(offset);
    faces.push_back(f);
  }
  mesh = SurfaceMesh(std::move(x), std::move(faces));
  return offset;
}

void start_relaxation(const SurfaceMesh& mesh, SurfaceAttributes& attrs,
                      const std::vector<VertexId>& merged, const std::vector<bool>& also) {
  std::vector<bool> congruent(mesh.num_faces(), false);
  for (std::size_t f = 0; f < also.size() && f < congruent.size(); ++f) congruent[f] = also[f];
  for (const auto v : merged)
    for (const auto f : mesh.vertex_faces(v)) congruent[f.index()] = true;
  // A part-way relaxation is folded in: its current rest shape is the base of the new y0.
  const RestState base =
      attrs.relax_from ? rest_at(*attrs.relax_from, attrs.rest, attrs.relax_s) : attrs.rest;
  attrs.relax_from = congruent_rest(mesh.faces(), attrs.state, base, congruent);
  attrs.relax_s = 0.0;
}

void check_attributes(const SurfaceMesh& mesh, const SurfaceAttributes& a) {
  const std::size_t nv = mesh.num_vertices(), nf = mesh.num_faces();
  auto fail = [](const std::string& channel, std::size_t got, std::size_t want) {
    throw Error("surface attributes: channel '" + channel + "' has " + std::to_string(got) +
                " entries, the mesh needs " + std::to_string(want));
  };
  if (a.state.x.size() != nv) fail("state.x", a.state.x.size(), nv);
  if (a.state.D.size() != nv) fail("state.D", a.state.D.size(), nv);
  if (a.reference.size() != nv) fail("reference", a.reference.size(), nv);
  if (a.rest.elements.size() != nf) fail("rest", a.rest.elements.size(), nf);
  if (a.relax_from && a.relax_from->elements.size() != nf)
    fail("relax_from", a.relax_from->elements.size(), nf);
  if (a.face_material.size() != nf) fail("face_material", a.face_material.size(), nf);
  for (const int m : a.face_material)
    if (m < 0 || static_cast<std::size_t>(m) >= a.materials.size())
      fail("face_material (material index)", static_cast<std::size_t>(m), a.materials.size());
  if (!a.constraints.fixed.empty() && a.constraints.fixed.size() != nv)
    fail("constraints", a.constraints.fixed.size(), nv);
  if (a.velocity.size() != 0 && (nv == 0 || a.velocity.size() % static_cast<Eigen::Index>(nv) != 0))
    fail("velocity", static_cast<std::size_t>(a.velocity.size()), nv);
  for (const Loads* l : {&a.applied_loads, &a.pending_loads}) {
    for (const auto& n : l->nodal)
      if (n.node >= nv) fail("loads (nodal load vertex)", n.node, nv);
    for (const auto& p : l->pressures)
      for (const auto f : p.faces)
        if (f.index() >= nf) fail("loads (pressure face)", f.index(), nf);
  }
  for (const auto* chains : {&a.marks.incisions, &a.marks.sutures})
    for (const auto& c : *chains)
      for (const auto v : c)
        if (v.index() >= nv) fail("marks (vertex)", v.index(), nv);
}

}  // namespace sutura::engine
