#include "surgery_edits.hpp"

#include <algorithm>

#include "sutura/engine/surgery/carry.hpp"
#include "sutura/engine/surgery/relaxation.hpp"

namespace sutura::app::detail {

namespace {

// New vertex standing for each old vertex: the new vertex with the largest weight on it
// (a copy, a merge containing it, or the nearest inserted point); invalid when removed.
std::vector<engine::VertexId> vertex_images(const engine::EditMaps& maps, std::size_t old_count) {
  std::vector<engine::VertexId> image(old_count);
  std::vector<double> best(old_count, 0.0);
  for (std::size_t v = 0; v < maps.vertices.size(); ++v) {
    const auto& o = maps.vertices[v];
    for (std::size_t i = 0; i < o.parents.size(); ++i) {
      const std::size_t p = o.parents[i].index();
      // Strictly greater: the first (lowest new id) wins ties, e.g. the lip that kept the id.
      if (p < old_count && o.weights[i] > best[p]) {
        best[p] = o.weights[i];
        image[p] = engine::VertexId(v);
      }
    }
  }
  return image;
}

engine::Loads carry_loads(const engine::EditMaps& maps, const engine::Loads& old,
                          const std::vector<engine::VertexId>& image) {
  engine::Loads out = old;
  out.nodal.clear();
  for (const auto& n : old.nodal) {
    if (n.node >= image.size() || !image[n.node].valid()) continue;  // removed with its region
    auto moved = n;
    moved.node = image[n.node].index();
    out.nodal.push_back(moved);
  }
  for (auto& p : out.pressures)
    if (!p.faces.empty()) p.faces = engine::carry_face_set(maps, p.faces);
  return out;
}

std::vector<engine::VertexId> carry_chain(const std::vector<engine::VertexId>& chain,
                                          const std::vector<engine::VertexId>& image) {
  std::vector<engine::VertexId> out;
  for (const auto v : chain)
    if (v.index() < image.size() && image[v.index()].valid() &&
        (out.empty() || out.back() != image[v.index()]))
      out.push_back(image[v.index()]);
  return out;
}

}  // namespace

void apply_edit(SceneObject& obj, engine::SurfaceMesh mesh, const engine::EditMaps& maps) {
  SimulationData& sim = obj.sim;
  const auto image = vertex_images(maps, obj.mesh.num_vertices());
  sim.state = engine::carry_state(maps, sim.state);
  sim.rest = engine::carry_rest(maps, sim.rest);
  if (sim.relax_from) sim.relax_from = engine::carry_rest(maps, *sim.relax_from);
  sim.face_material = engine::carry_face_values(maps, sim.face_material);
  sim.constraints = engine::carry_constraints(maps, sim.constraints);
  sim.applied_loads = carry_loads(maps, sim.applied_loads, image);
  sim.pending_loads = carry_loads(maps, sim.pending_loads, image);
  sim.velocity.resize(0);
  sim.reference = engine::carry_points(maps, sim.reference);
  for (auto* marks : {&obj.marks.incisions, &obj.marks.sutures})
    for (auto& chain : *marks) chain = carry_chain(chain, image);
  mesh.set_positions(sim.state.x);
  obj.mesh = std::move(mesh);
}

std::size_t append_component(SceneObject& obj, const engine::SurfaceMesh& placed,
                             const engine::SurfaceMesh& rest_shape,
                             const engine::ShellMaterial& material) {
  SimulationData& sim = obj.sim;
  const std::size_t offset = obj.mesh.num_vertices();
  const std::size_t face_offset = obj.mesh.num_faces();
  std::vector<engine::Vec3> x = obj.mesh.positions();
  std::vector<engine::FaceIndices> faces = obj.mesh.faces();
  for (const auto& p : placed.positions()) x.push_back(p);
  for (auto f : placed.faces()) {
    for (auto& v : f) v += static_cast<int>(offset);
    faces.push_back(f);
  }
  const engine::ShellState patch_rest_state = engine::state_from_mesh(rest_shape);
  const engine::RestState patch_rest = engine::rest_from_state(rest_shape, patch_rest_state);
  for (const auto& p : placed.positions()) {
    sim.state.x.push_back(p);
    sim.state.D.push_back(engine::Quat::Identity());
    sim.reference.push_back(p);
  }
  sim.rest.elements.insert(sim.rest.elements.end(), patch_rest.elements.begin(),
                           patch_rest.elements.end());
  if (sim.relax_from)
    sim.relax_from->elements.insert(sim.relax_from->elements.end(), patch_rest.elements.begin(),
                                    patch_rest.elements.end());
  sim.materials.push_back(material);
  sim.face_material.resize(face_offset, 0);
  sim.face_material.resize(faces.size(), static_cast<int>(sim.materials.size() - 1));
  if (!sim.constraints.fixed.empty()) sim.constraints.fixed.resize(x.size(), 0);
  sim.velocity.resize(0);
  obj.mesh = engine::SurfaceMesh(std::move(x), std::move(faces));
  return offset;
}

void start_relaxation(SceneObject& obj, const std::vector<engine::VertexId>& merged,
                      const std::vector<bool>& also) {
  SimulationData& sim = obj.sim;
  std::vector<bool> congruent(obj.mesh.num_faces(), false);
  for (std::size_t f = 0; f < also.size() && f < congruent.size(); ++f) congruent[f] = also[f];
  for (const auto v : merged)
    for (const auto f : obj.mesh.vertex_faces(v)) congruent[f.index()] = true;
  // A part-way relaxation is folded in: its current rest shape is the base of the new y0.
  engine::RestState base = sim.relax_from ? engine::rest_at(*sim.relax_from, sim.rest, sim.relax_s)
                                          : sim.rest;
  sim.relax_from = engine::congruent_rest(obj.mesh.faces(), sim.state, base, congruent);
  sim.relax_s = 0.0;
}

}  // namespace sutura::app::detail
