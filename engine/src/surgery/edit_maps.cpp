#include "sutura/engine/surgery/edit_maps.hpp"

#include <algorithm>
#include <map>

namespace sutura::engine {

EditMaps EditMaps::identity(std::size_t nv, std::size_t nf) {
  EditMaps m;
  m.vertices.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    m.vertices[v].parents = {VertexId(v)};
    m.vertices[v].weights = {1.0};
  }
  m.faces.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) m.faces[f].parent = FaceId(f);
  return m;
}

EditMaps compose(const EditMaps& first, const EditMaps& second) {
  EditMaps out;
  out.vertices.resize(second.vertices.size());
  for (std::size_t v = 0; v < second.vertices.size(); ++v) {
    const VertexOrigin& o2 = second.vertices[v];
    std::map<std::int32_t, double> acc;  // ordered: deterministic parent order
    VertexOriginKind kind = o2.kind;
    for (std::size_t i = 0; i < o2.parents.size(); ++i) {
      const VertexOrigin& o1 = first.vertices[o2.parents[i].index()];
      kind = std::max(kind, o1.kind);
      for (std::size_t j = 0; j < o1.parents.size(); ++j)
        acc[o1.parents[j].value] += o2.weights[i] * o1.weights[j];
    }
    VertexOrigin& o = out.vertices[v];
    o.kind = kind;
    for (const auto& [id, w] : acc) {
      o.parents.emplace_back(id);
      o.weights.push_back(w);
    }
  }
  out.faces.resize(second.faces.size());
  for (std::size_t f = 0; f < second.faces.size(); ++f) {
    const FaceOrigin& o2 = second.faces[f];
    const FaceOrigin& o1 = first.faces[o2.parent.index()];
    out.faces[f].parent = o1.parent;
    out.faces[f].bary = o2.bary * o1.bary;
    out.faces[f].kind = std::max(o1.kind, o2.kind);
  }
  return out;
}

}  // namespace sutura::engine
