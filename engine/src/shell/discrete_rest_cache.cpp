#include "discrete_rest_cache.hpp"

#include "dihedral_angle.hpp"
#include "parallel_loop.hpp"
#include "rest_key.hpp"

namespace sutura::engine::dshell {
namespace {

FaceStencil make_stencil(const HingeTopology& topo, const FaceIndices& face, std::size_t f) {
  FaceStencil st;
  const auto add = [&st](int slot, std::int32_t node) {
    st.slot[st.size] = slot;
    st.node[st.size] = node;
    ++st.size;
  };
  for (int k = 0; k < 3; ++k) add(k, face[k]);
  for (int k = 0; k < 3; ++k) {
    const std::int32_t h = topo.face_hinge[f][k];
    if (h < 0) continue;
    const Hinge& hg = topo.hinges[h];
    st.side[k] = hg.face[0] == static_cast<std::int32_t>(f) ? 0 : 1;
    // The apex across the edge is the other face's apex: d seen from face[0], c from face[1].
    add(3 + k, hg.node[st.side[k] == 0 ? 3 : 2]);
  }
  return st;
}

void build_face(const ShellProblem& p, const HingeTopology& topo, std::size_t f, CstRest& cst,
                FaceBending& bending) {
  const ShellMaterial& mat = (*p.materials)[(*p.face_material)[f]];
  const auto& X = p.rest->elements[f].X;
  std::array<bool, 3> interior{};
  for (int k = 0; k < 3; ++k) interior[k] = topo.face_hinge[f][k] >= 0;
  cst = make_cst_rest(X, mat);
  bending = make_face_bending(X, mat, interior);
}

double hinge_rest_angle(const ShellProblem& p, const Hinge& hg) {
  const auto& rest = p.rest->elements;
  const int kf = hg.halfedge[0];
  const int kg = hg.halfedge[1];
  // a is corner kf of f and corner kg+1 of g; b is corner kf+1 of f and corner kg of g.
  return rest_dihedral_angle(rest[hg.face[0]], kf, (kf + 1) % 3, rest[hg.face[1]], (kg + 1) % 3,
                             kg);
}

/// Rest angles of the hinges for which keep(h) is false.
template <class Keep>
void update_hinges(const ShellProblem& p, DiscreteRestData& d, Keep&& keep) {
  for_each_index(d.topo.hinges.size(), [&](std::size_t h) {
    if (!keep(h)) d.theta_rest[h] = hinge_rest_angle(p, d.topo.hinges[h]);
  });
}

}  // namespace

void build_discrete_rest_data(const ShellProblem& p, DiscreteRestData& out) {
  const std::vector<FaceIndices>& faces = *p.faces;
  out.topo = build_hinge_topology(faces);
  const std::size_t F = faces.size();
  out.stencil.resize(F);
  out.cst.resize(F);
  out.bending.resize(F);
  for_each_index(F, [&](std::size_t f) {
    out.stencil[f] = make_stencil(out.topo, faces[f], f);
    build_face(p, out.topo, f, out.cst[f], out.bending[f]);
  });
  out.theta_rest.resize(out.topo.hinges.size());
  update_hinges(p, out, [](std::size_t) { return false; });
}

const DiscreteRestData& DiscreteRestCache::update(const ShellProblem& p) {
  const std::vector<FaceIndices>& faces = *p.faces;
  const std::size_t F = faces.size();
  const auto material_of = [&p](std::size_t f) -> const ShellMaterial& {
    return (*p.materials)[(*p.face_material)[f]];
  };
  if (!(valid_ && key_faces_ == faces)) {
    // A new mesh: everything from scratch, by the same path as a call without the memo.
    valid_ = false;  // stays so if the topology throws
    build_discrete_rest_data(p, data_);
    key_faces_ = faces;
    key_rest_ = p.rest->elements;
    key_material_.resize(F);
    for (std::size_t f = 0; f < F; ++f) key_material_[f] = material_of(f);
    valid_ = true;
    return data_;
  }
  std::vector<unsigned char> rebuilt(F, 0);
  for_each_index(F, [&](std::size_t f) {
    const ElementRest& rest = p.rest->elements[f];
    const ShellMaterial& mat = material_of(f);
    if (same_bits(key_rest_[f], rest) && same_bits(key_material_[f], mat)) return;
    key_rest_[f] = rest;
    key_material_[f] = mat;
    build_face(p, data_.topo, f, data_.cst[f], data_.bending[f]);
    rebuilt[f] = 1;
  });
  update_hinges(p, data_, [&](std::size_t h) {
    const Hinge& hg = data_.topo.hinges[h];
    return rebuilt[hg.face[0]] == 0 && rebuilt[hg.face[1]] == 0;
  });
  return data_;
}

}  // namespace sutura::engine::dshell
