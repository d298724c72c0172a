#include "session_defaults.hpp"

#include <stdexcept>
#include <string>

#include "sutura/app/session.hpp"

namespace sutura::app::detail {

namespace {

// A field added to (or removed from) an engine struct changes its size: give the field its
// session value below, for every format version, then update the size here. Sizes are those
// of x86-64 with libstdc++ (GCC and Clang alike); elsewhere the check is skipped.
#if defined(__x86_64__) && defined(__GLIBCXX__)
static_assert(sizeof(engine::PcgParams) == 16, "PcgParams changed: pin the new field below");
static_assert(sizeof(engine::StaticSolverParams) == 160,
              "StaticSolverParams changed: pin the new field in static_solver_defaults");
static_assert(sizeof(engine::DynamicsParams) == 128,
              "DynamicsParams changed: pin the new field in dynamics_defaults");
static_assert(sizeof(engine::RelaxationParams) == 360,
              "RelaxationParams changed: pin the new field in relaxation_defaults");
static_assert(sizeof(engine::UnloadParams) == 184, "UnloadParams changed: pin the new field in unload_defaults");
static_assert(sizeof(engine::ContactParams) == 24, "ContactParams changed: pin the new field in contact_defaults");
static_assert(sizeof(engine::AreaBarrierParams) == 16,
              "AreaBarrierParams changed: pin the new field in area_barrier_defaults");
static_assert(sizeof(engine::RemeshPasses) == 24,
              "RemeshPasses changed: pin the new field in remesh_passes_defaults");
static_assert(sizeof(engine::ResampleChainsParams) == 184,
              "ResampleChainsParams changed: pin the new field in seam_defaults");
static_assert(sizeof(engine::JoinParams) == 56, "JoinParams changed: pin the new field in join_defaults");
static_assert(sizeof(engine::IncisionParams) == 160,
              "IncisionParams changed: pin the new field in incision_defaults");
static_assert(sizeof(engine::PatchPlanParams) == 88,
              "PatchPlanParams changed: pin the new field in patch_plan_defaults");
static_assert(sizeof(engine::PrepareParams) == 96,
              "PrepareParams changed: pin the new field in prepare_defaults");
static_assert(sizeof(engine::ResectionParams) == 16,
              "ResectionParams changed: pin the new field in resection_defaults");
#endif

// A field that fits in a struct's padding leaves its size as it was. For the structs with room
// in theirs, a structured binding, which must name every field, stops the build instead.
[[maybe_unused]] void check_field_counts() {
  [[maybe_unused]] auto [r1, r2, r3] = engine::RemeshPasses{};
  [[maybe_unused]] auto [s1, s2, s3, s4, s5, s6, s7, s8, s9] = engine::ResampleChainsParams{};
  [[maybe_unused]] auto [j1, j2, j3, j4, j5] = engine::JoinParams{};
  [[maybe_unused]] auto [p1, p2, p3, p4, p5, p6, p7, p8, p9, p10] = engine::PrepareParams{};
}

void check_version(int version) {
  if (version < 1 || version > kSessionFormatVersion)
    throw std::invalid_argument("session format version " + std::to_string(version) +
                                " has no defaults in this build (1 to " +
                                std::to_string(kSessionFormatVersion) + ")");
}

engine::PcgParams pcg_defaults() {
  engine::PcgParams p;
  p.tolerance = 1e-10;
  p.max_iterations = 20000;
  return p;
}

}  // namespace

// Versions 1 to 5 share every value below (the versions differ in surgery ops only).
engine::StaticSolverParams static_solver_defaults(int version) {
  check_version(version);
  engine::StaticSolverParams p;
  p.lambda_start = 0.0;
  p.lambda_end = 1.0;
  p.load_steps = 1;
  p.tolerance = 1e-8;
  p.max_iterations = 30;
  p.line_search = true;
  p.max_step_cuts = 6;
  p.energy_blowup = 1e12;
  p.energy_reference = 0.0;
  p.force_reference = 0.0;
  p.shift_indefinite = false;
  p.quasi_newton_steps = 30;
  p.single_precision_solves = true;
  p.min_area_ratio = 1e-2;
  p.linear_solver = engine::LinearSolverKind::Cholmod;
  p.pcg = pcg_defaults();
  p.linear = false;
  p.keep_going = nullptr;
  return p;
}

engine::DynamicsParams dynamics_defaults(int version) {
  check_version(version);
  engine::DynamicsParams p;
  p.scheme = engine::DynamicsScheme::Linearized;  // the parser makes it Newton with a relaxation
  p.dt = 1e-3;
  p.steps = 100;
  p.mass_damping = 10.0;
  p.stiffness_damping = 1e-3;
  p.tolerance = 1e-6;
  p.max_iterations = 20;
  p.max_step_cuts = 4;
  p.min_area_ratio = 1e-2;
  p.force_reference = 0.0;
  p.single_precision_solves = true;
  p.corotated_damping = true;
  p.linear_solver = engine::LinearSolverKind::Cholmod;
  p.keep_going = nullptr;
  p.pcg = pcg_defaults();
  return p;
}

engine::RelaxationParams relaxation_defaults(int version) {
  check_version(version);
  engine::RelaxationParams p;
  p.solver = engine::RelaxationSolver::Static;
  p.steps = 10;
  p.s_start = 0.0;
  p.s_end = 1.0;
  p.settle = true;
  p.settle_steps = 20;
  p.max_cuts = 6;
  p.increment_tolerance = 1e-6;
  p.predictor = true;
  p.check_stability = true;
  p.max_escapes = 3;
  p.density.reset();
  p.statics = static_solver_defaults(version);
  p.dynamics = dynamics_defaults(version);
  return p;
}

engine::UnloadParams unload_defaults(int version) {
  check_version(version);
  engine::UnloadParams p;
  p.max_iterations = 20;
  p.tolerance = 0.0;
  p.acceleration_depth = 5;
  p.solver = static_solver_defaults(version);
  return p;
}

engine::ContactParams contact_defaults(int version) {
  check_version(version);
  engine::ContactParams p;
  p.distance = 0.5;
  p.stiffness = 1.0;
  p.project_hessian = true;
  return p;
}

engine::AreaBarrierParams area_barrier_defaults(int version) {
  check_version(version);
  engine::AreaBarrierParams p;
  p.activation = 0.25;
  p.factor = 1.0;
  return p;
}

// Surgery ops: each version's values; the versions differ where the table in
// docs/session-format.md says so.
engine::RemeshPasses remesh_passes_defaults(int version) {
  check_version(version);
  engine::RemeshPasses p;
  p.iterations = 3;
  p.raise_angles_below_deg = 25.0;
  p.rim_faces_in_region = false;
  return p;
}

engine::ResampleChainsParams seam_defaults(int version) {
  check_version(version);
  engine::ResampleChainsParams p;
  p.target_edge_length = 0.0;
  p.band_width = 2.0;
  p.grading = 1.0;
  p.band_passes = remesh_passes_defaults(version);
  p.constrained_vertices.clear();
  p.constrained_edges.clear();
  p.frozen_faces.clear();
  p.rest_edge_lengths.clear();
  p.corner_turn_deg = 120.0;
  return p;
}

engine::JoinParams join_defaults(int version) {
  check_version(version);
  engine::JoinParams p;
  p.placement = engine::SuturePlacement::Mean;
  p.pairing = engine::JoinPairing::ArcLength;
  p.held.clear();
  p.rigid_iterations = 20;
  p.rigid_stages = 8;
  return p;
}

engine::IncisionParams incision_defaults(int version) {
  check_version(version);
  engine::IncisionParams p;
  p.mode = engine::IncisionMode::CutThroughFaces;
  p.max_distance = 1.0;
  p.end_snap = 0.25;
  p.remesh = version >= 2;  // version 1 sessions keep the raw trace
  p.target_edge_length = 0.0;
  p.band_width = 2.0;
  p.grading = 1.0;
  p.repair_below_deg = version >= 4 ? 20.0 : 0.0;
  p.repair_attempts = version >= 5 ? 5 : 3;
  p.band_passes = remesh_passes_defaults(version);
  p.band_passes.rim_faces_in_region = version >= 5;
  p.constrained_vertices.clear();
  p.constrained_edges.clear();
  return p;
}

engine::PatchPlanParams patch_plan_defaults(int version) {
  check_version(version);
  engine::PatchPlanParams p;
  p.shape = engine::PatchShape::Ellipse;
  p.width = 4.0;
  p.length = 0.0;
  p.edge_length = 0.0;
  p.min_edge_length = 0.0;
  p.max_distance = 1.0;
  p.left_segments = p.right_segments = 0;
  p.seam_passes = remesh_passes_defaults(version);
  p.max_faces = 2.0e7;
  return p;
}

engine::PrepareParams prepare_defaults(int version) {
  check_version(version);
  engine::PrepareParams p;
  p.clips.clear();
  p.edge_length.reset();
  p.keep_caps = false;
  p.smoothing_iterations = 10;
  p.smoothing_bound = 0.02;
  p.remesh_iterations = 5;
  p.drop_area_fraction = 0.05;
  p.crease_angle_deg = 45.0;
  p.coarsen_in_halves_from = 200'000;
  p.max_faces = 2'000'000;
  return p;
}

engine::ResectionParams resection_defaults(int version) {
  check_version(version);
  engine::ResectionParams p;
  p.radius = 10.0;
  p.sliver_fraction = 0.15;
  return p;
}

}  // namespace sutura::app::detail
