#pragma once
// Model 2's state-independent data and its memo (private to engine/src/shell).
//
// Why: the hinge topology (a sort of the 3F half-edges), each face's CST rest data and plate
// bending coefficients and each hinge's rest dihedral angle depend only on the faces, the
// per-element rest state and the materials, yet every evaluation needed them: at 5k faces
// they cost more than the energy and gradient themselves (6.6 ms for a gradient, serial).
//
// Contract: transparent, like model 1's ElementStiffnessCache. The topology is kept while the
// face array is equal; a face's data while its rest corners, rest triads and material are
// bitwise the ones it was built from and the topology is kept; a hinge's rest angle while
// both its faces' data are kept. Anything else is rebuilt with the same functions, so results
// are bit-identical with or without the memo and the model stays a pure function of its
// inputs. Memory: about 0.7 kB per face.
//
// Threads: whole calls are serialised by `mutex`; a caller that cannot take it (the GUI
// measuring while a solver runs) builds its own DiscreteRestData instead of waiting.
#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

#include "cst_membrane.hpp"
#include "hinge_bending.hpp"
#include "hinge_topology.hpp"
#include "sutura/engine/shell/shell_model.hpp"

namespace sutura::engine::dshell {

/// A face's bending stencil: its 3 corners (slots 0..2) and the apexes across its interior
/// edges (slot 3 + k across half-edge k), in that order.
struct FaceStencil {
  std::array<int, 6> slot{};
  std::array<std::int32_t, 6> node{};
  int size = 0;
  /// Per half-edge k: the face's side (0, 1) in the hinge across it, -1 on the boundary.
  std::array<int, 3> side{-1, -1, -1};
};

struct DiscreteRestData {
  HingeTopology topo;
  std::vector<FaceStencil> stencil;  ///< per face
  std::vector<CstRest> cst;          ///< per face
  std::vector<FaceBending> bending;  ///< per face
  std::vector<double> theta_rest;    ///< per hinge, rad
};

/// Builds everything from scratch. The problem must be valid (check_problem in
/// discrete_shell.cpp); throws TopologyError for a non-manifold or inconsistently oriented
/// face array.
void build_discrete_rest_data(const ShellProblem& p, DiscreteRestData& out);

class DiscreteRestCache {
 public:
  /// The data for this (valid) problem, rebuilt where its inputs changed (see the contract
  /// above). Throws like build_discrete_rest_data; the memo then holds nothing.
  const DiscreteRestData& update(const ShellProblem& p);

  std::mutex mutex;

 private:
  std::vector<FaceIndices> key_faces_;
  std::vector<ElementRest> key_rest_;
  std::vector<ShellMaterial> key_material_;
  bool valid_ = false;
  DiscreteRestData data_;
};

}  // namespace sutura::engine::dshell
