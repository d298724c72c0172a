#pragma once
// The objects a session works on, by name, in the order they were created.
//
// Copies share objects (copy-on-write): copying a Workspace copies one pointer per object,
// and an object is copied only when it is edited through a workspace that shares it. The
// undo history (app/src/replay_surgery_ops.cpp, Run::remember) is therefore a list of
// workspaces in which an op that changed one object of ten holds one new object, not ten.
// Not thread-safe: a workspace and its copies are used from one thread at a time.
#include <cstddef>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "sutura/engine/anatomy/aortic_arch.hpp"
#include "sutura/engine/measure/vertex_fields.hpp"
#include "sutura/engine/mesh.hpp"
#include "sutura/engine/surgery/surface_attributes.hpp"

namespace sutura::app {

struct SceneObject {
  std::string name;
  engine::SurfaceMesh mesh;    ///< current state
  engine::SurfaceMesh before;  ///< pre-operative state: the mesh as generated or loaded
  /// Model 1's measures of the pre-operative state per vertex of `before`, when that state is
  /// stressed: set by `unload` (the imaged vessel in equilibrium under its loads). Empty
  /// vectors: the pre-operative state is the stress-free one, zero everywhere.
  engine::VertexMeasures before_measures;
  /// Everything simulated or drawn on `mesh`, carried across every edit by the engine
  /// (state, rest shape and pending y0, materials, constraints, loads, velocity, reference
  /// positions, marks).
  engine::SurfaceAttributes sim;
  /// The open ends as the mesh came, named (from a landmarks file given to `load`, or by
  /// `prepare`): centre, normal and radius where each was. end_name() matches them to the
  /// boundary loops of the mesh now.
  std::vector<engine::VesselEnd> ends;
};

/// Whether a suture made since the last relaxing run waits to be relaxed (a pending y0). O(1).
bool has_pending_relaxation(const SceneObject& obj);

/// Whether every vertex has a pre-operative (reference) position, from which displacements are
/// measured (they follow edits; a part added by an edit may have none). O(1).
bool has_reference_positions(const SceneObject& obj);

/// One material region of an object: the faces with one of its materials (the first is the
/// wall, the others patches).
struct MaterialRegion {
  engine::ShellMaterial material;
  std::size_t faces = 0;  ///< 0: a patch undone or cut away
};

/// The object's material regions, one per material, in the order of its materials (a face
/// whose material index is out of range counts in none). O(materials + F).
std::vector<MaterialRegion> material_regions(const SceneObject& obj);

/// The mean position of `loop`'s vertices in `mesh` (a boundary loop's centre). O(loop).
engine::Vec3 loop_centroid(const engine::SurfaceMesh& mesh, const std::vector<engine::VertexId>& loop);

/// The name of the end whose boundary loop `loop` (vertices of obj.mesh) is: the named end
/// whose centre lies within half its radius (at least 0.5 mm) of the loop's centroid, or ""
/// (an end made by an edit, or one an incision has opened into a cut). O(loop + ends).
std::string end_name(const SceneObject& obj, const std::vector<engine::VertexId>& loop);

class Workspace {
  using Slots = std::vector<std::shared_ptr<SceneObject>>;

 public:
  /// Read-only view of the objects in creation order (a random-access range of
  /// `const SceneObject&`). Invalidated by add(), edit() and assignment.
  class Objects {
   public:
    class iterator {
     public:
      using iterator_category = std::forward_iterator_tag;
      using value_type = SceneObject;
      using difference_type = std::ptrdiff_t;
      using pointer = const SceneObject*;
      using reference = const SceneObject&;
      iterator() = default;
      explicit iterator(Slots::const_iterator it) : it_(it) {}
      reference operator*() const { return **it_; }
      pointer operator->() const { return it_->get(); }
      iterator& operator++() { ++it_; return *this; }
      iterator operator++(int) { iterator t = *this; ++it_; return t; }
      bool operator==(const iterator& o) const { return it_ == o.it_; }
      bool operator!=(const iterator& o) const { return it_ != o.it_; }

     private:
      Slots::const_iterator it_;
    };
    explicit Objects(const Slots& slots) : slots_(&slots) {}
    [[nodiscard]] iterator begin() const { return iterator(slots_->begin()); }
    [[nodiscard]] iterator end() const { return iterator(slots_->end()); }
    [[nodiscard]] std::size_t size() const { return slots_->size(); }
    [[nodiscard]] bool empty() const { return slots_->empty(); }
    [[nodiscard]] const SceneObject& operator[](std::size_t i) const { return *(*slots_)[i]; }
    [[nodiscard]] const SceneObject& front() const { return *slots_->front(); }

   private:
    const Slots* slots_;
  };

  /// Adds an object at rest (rest state congruent with the mesh, identity nodal triads,
  /// default material); throws std::invalid_argument if the name is taken.
  SceneObject& add(std::string name, engine::SurfaceMesh mesh);
  /// The object to change, copied first if another workspace shares it (O(object size)
  /// then, O(objects) otherwise); nullptr when no object has that name. The reference stays
  /// valid until the next add() or assignment; a copy of this workspace made while it is
  /// held shares the object, so take copies before editing, never in between.
  [[nodiscard]] SceneObject* edit(const std::string& name);
  /// nullptr when no object has that name.
  [[nodiscard]] const SceneObject* find(const std::string& name) const;
  [[nodiscard]] Objects objects() const { return Objects(objects_); }
  /// "a, b, c" for messages.
  [[nodiscard]] std::string names() const;

 private:
  Slots objects_;
};

}  // namespace sutura::app
