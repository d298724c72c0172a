// What a solver or surgery op means where a session line leaves a field out is pinned per
// format version (app/src/session_defaults.hpp), not taken from the engine's member defaults:
// these are the values every recorded session of versions 1 to 5 was replayed with. A change here changes
// what recorded sessions mean (tests/golden/position_hashes.txt shows it on the bundled ones).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "../../app/src/session_defaults.hpp"
#include "sutura/app/session.hpp"

using namespace sutura;
using namespace sutura::app::detail;

namespace {

app::Session parse_at(int version, const std::string& lines) {
  return app::parse_session(
      "{\"format\": \"sutura-session\", \"version\": " + std::to_string(version) + "}\n" + lines,
      "/tmp/defaults.jsonl");
}

}  // namespace

TEST(SessionDefaults, SolverSettingsArePinnedForEveryVersion) {
  for (int v = 1; v <= app::kSessionFormatVersion; ++v) {
    SCOPED_TRACE(v);
    const engine::StaticSolverParams s = static_solver_defaults(v);
    EXPECT_EQ(s.load_steps, 1);
    EXPECT_EQ(s.tolerance, 1e-8);
    EXPECT_EQ(s.max_iterations, 30);
    EXPECT_TRUE(s.line_search);
    EXPECT_EQ(s.max_step_cuts, 6);
    EXPECT_EQ(s.energy_blowup, 1e12);
    EXPECT_FALSE(s.shift_indefinite);
    EXPECT_EQ(s.quasi_newton_steps, 30);
    EXPECT_TRUE(s.single_precision_solves);
    EXPECT_EQ(s.min_area_ratio, 1e-2);
    EXPECT_EQ(s.linear_solver, engine::LinearSolverKind::Cholmod);
    EXPECT_EQ(s.pcg.tolerance, 1e-10);
    EXPECT_EQ(s.pcg.max_iterations, 20000);
    EXPECT_FALSE(s.linear);
    EXPECT_FALSE(s.keep_going);

    const engine::DynamicsParams d = dynamics_defaults(v);
    EXPECT_EQ(d.scheme, engine::DynamicsScheme::Linearized);
    EXPECT_EQ(d.dt, 1e-3);
    EXPECT_EQ(d.steps, 100);
    EXPECT_EQ(d.mass_damping, 10.0);
    EXPECT_EQ(d.stiffness_damping, 1e-3);
    EXPECT_EQ(d.tolerance, 1e-6);
    EXPECT_EQ(d.max_iterations, 20);
    EXPECT_EQ(d.max_step_cuts, 4);
    EXPECT_EQ(d.min_area_ratio, 1e-2);
    EXPECT_TRUE(d.single_precision_solves);
    EXPECT_TRUE(d.corotated_damping);

    const engine::RelaxationParams r = relaxation_defaults(v);
    EXPECT_EQ(r.solver, engine::RelaxationSolver::Static);
    EXPECT_EQ(r.steps, 10);
    EXPECT_EQ(r.s_end, 1.0);
    EXPECT_TRUE(r.settle);
    EXPECT_EQ(r.settle_steps, 20);
    EXPECT_EQ(r.max_cuts, 6);
    EXPECT_EQ(r.increment_tolerance, 1e-6);
    EXPECT_TRUE(r.predictor);
    EXPECT_TRUE(r.check_stability);
    EXPECT_EQ(r.max_escapes, 3);
    EXPECT_FALSE(r.density.has_value());
    EXPECT_EQ(r.statics.tolerance, 1e-8);
    EXPECT_EQ(r.dynamics.dt, 1e-3);

    const engine::UnloadParams u = unload_defaults(v);
    EXPECT_EQ(u.max_iterations, 20);
    EXPECT_EQ(u.tolerance, 0.0);
    EXPECT_EQ(u.acceleration_depth, 5);
    EXPECT_EQ(contact_defaults(v).distance, 0.5);
    EXPECT_EQ(contact_defaults(v).stiffness, 1.0);
    EXPECT_TRUE(contact_defaults(v).project_hessian);
    EXPECT_EQ(area_barrier_defaults(v).activation, 0.25);
    EXPECT_EQ(area_barrier_defaults(v).factor, 1.0);
  }
  EXPECT_THROW(static_solver_defaults(0), std::invalid_argument);
  EXPECT_THROW(dynamics_defaults(app::kSessionFormatVersion + 1), std::invalid_argument);
}

// A line that gives nothing gets the file's version's values, and a field a line gives changes
// that field only (relax, contact and unload included). While the pinned values equal the
// engine's own defaults, this cannot tell which of the two the parser started from: the size
// checks and the golden position hashes are what catch an engine default that moves.
TEST(SessionDefaults, GivenFieldsOverrideAndTheRestKeepTheVersionsValues) {
  for (int v : {1, app::kSessionFormatVersion}) {
    SCOPED_TRACE(v);
    const app::Session s = parse_at(
        v, "{\"op\": \"solve\"}\n"
           "{\"op\": \"solve\", \"tolerance\": 1e-6}\n"
           "{\"op\": \"simulate\", \"relax\": {\"steps\": 4}, \"contact\": {}}\n"
           "{\"op\": \"unload\", \"object\": \"a\"}\n");
    const auto& plain = std::get<app::SolveOp>(s.actions.at(0).op);
    const engine::StaticSolverParams pinned = static_solver_defaults(v);
    EXPECT_EQ(plain.params.tolerance, pinned.tolerance);
    EXPECT_EQ(plain.params.max_iterations, pinned.max_iterations);
    EXPECT_EQ(plain.params.quasi_newton_steps, pinned.quasi_newton_steps);
    EXPECT_EQ(plain.barrier.activation, area_barrier_defaults(v).activation);
    const auto& given = std::get<app::SolveOp>(s.actions.at(1).op);
    EXPECT_EQ(given.params.tolerance, 1e-6);
    EXPECT_EQ(given.params.max_iterations, pinned.max_iterations);
    const auto& sim = std::get<app::SimulateOp>(s.actions.at(2).op);
    ASSERT_TRUE(sim.relax.has_value());
    EXPECT_EQ(sim.relax->steps, 4);
    EXPECT_EQ(sim.relax->max_escapes, relaxation_defaults(v).max_escapes);
    EXPECT_EQ(sim.relax->increment_tolerance, relaxation_defaults(v).increment_tolerance);
    EXPECT_EQ(sim.relax->statics.max_iterations, pinned.max_iterations);
    EXPECT_EQ(sim.params.mass_damping, dynamics_defaults(v).mass_damping);
    EXPECT_EQ(sim.params.scheme, engine::DynamicsScheme::Newton);  // with a relaxation
    ASSERT_TRUE(sim.contact.has_value());
    EXPECT_EQ(sim.contact->distance, contact_defaults(v).distance);
    const auto& unload = std::get<app::UnloadOp>(s.actions.at(3).op);
    EXPECT_EQ(unload.params.max_iterations, unload_defaults(v).max_iterations);
    EXPECT_EQ(unload.params.acceleration_depth, unload_defaults(v).acceleration_depth);
  }
}

// The surgery ops' settings are pinned too; the versions differ where docs/session-format.md's
// table says so (the band remesh since 2, its second, finer remesh since 4, two finer
// attempts and the faces split at the band's rim counted as the band's since 5).
TEST(SessionDefaults, SurgerySettingsArePinnedPerVersion) {
  for (int v = 1; v <= app::kSessionFormatVersion; ++v) {
    SCOPED_TRACE(v);
    const engine::IncisionParams i = incision_defaults(v);
    EXPECT_EQ(i.mode, engine::IncisionMode::CutThroughFaces);
    EXPECT_EQ(i.max_distance, 1.0);
    EXPECT_EQ(i.end_snap, 0.25);
    EXPECT_EQ(i.remesh, v >= 2);
    EXPECT_EQ(i.target_edge_length, 0.0);
    EXPECT_EQ(i.band_width, 2.0);
    EXPECT_EQ(i.grading, 1.0);
    EXPECT_EQ(i.repair_below_deg, v >= 4 ? 20.0 : 0.0);
    EXPECT_EQ(i.repair_attempts, v >= 5 ? 5 : 3);
    EXPECT_EQ(i.band_passes.iterations, 3);
    EXPECT_EQ(i.band_passes.raise_angles_below_deg, 25.0);
    EXPECT_EQ(i.band_passes.rim_faces_in_region, v >= 5);
    const engine::RemeshPasses passes = remesh_passes_defaults(v);
    EXPECT_EQ(passes.iterations, 3);
    EXPECT_EQ(passes.raise_angles_below_deg, 25.0);
    EXPECT_FALSE(passes.rim_faces_in_region);
    const engine::ResampleChainsParams seams = seam_defaults(v);
    EXPECT_EQ(seams.target_edge_length, 0.0);
    EXPECT_EQ(seams.band_width, 2.0);
    EXPECT_EQ(seams.grading, 1.0);
    EXPECT_EQ(seams.corner_turn_deg, 120.0);
    EXPECT_EQ(seams.band_passes.rim_faces_in_region, passes.rim_faces_in_region);
    const engine::JoinParams join = join_defaults(v);
    EXPECT_EQ(join.placement, engine::SuturePlacement::Mean);
    EXPECT_EQ(join.pairing, engine::JoinPairing::ArcLength);
    EXPECT_EQ(join.rigid_iterations, 20);
    EXPECT_EQ(join.rigid_stages, 8);
    const engine::PatchPlanParams p = patch_plan_defaults(v);
    EXPECT_EQ(p.seam_passes.raise_angles_below_deg, passes.raise_angles_below_deg);
    EXPECT_EQ(p.seam_passes.rim_faces_in_region, passes.rim_faces_in_region);
    EXPECT_EQ(p.shape, engine::PatchShape::Ellipse);
    EXPECT_EQ(p.width, 4.0);
    EXPECT_EQ(p.max_distance, 1.0);
    EXPECT_EQ(p.max_faces, 2.0e7);
    EXPECT_EQ(resection_defaults(v).radius, 10.0);
    EXPECT_EQ(resection_defaults(v).sliver_fraction, 0.15);
  }
  EXPECT_THROW(incision_defaults(app::kSessionFormatVersion + 1), std::invalid_argument);
  EXPECT_THROW(remesh_passes_defaults(0), std::invalid_argument);
  // Parsed: a line that gives nothing gets its file's version's values.
  for (int v = 3; v <= app::kSessionFormatVersion; ++v) {
    SCOPED_TRACE(v);
    const app::Session s = parse_at(v, "{\"op\": \"incise\", \"object\": \"a\", \"points\": [[0, 0, 0], [1, 0, 0]]}\n"
                                       "{\"op\": \"resect\", \"object\": \"a\", \"planes\": [{\"origin\": [0, 0, 0], "
                                       "\"normal\": [0, 0, 1]}], \"seed\": [0, 0, 1]}\n"
                                       "{\"op\": \"remesh\", \"object\": \"a\", \"iterations\": 5}\n"
                                       "{\"op\": \"join\", \"object\": \"a\", \"chains\": [{\"loop\": [0, 0, 0]}, "
                                       "{\"loop\": [0, 0, 1]}]}\n"
                                       "{\"op\": \"patch\", \"object\": \"a\", \"start\": [0, 0, 0], \"end\": [1, 0, 0]}\n");
    const engine::RemeshPasses passes = remesh_passes_defaults(v);
    // While every version has the engine's values these only show that the parser sets them
    // from the version; they tell versions apart once a value differs.
    const auto& resect = std::get<app::ResectOp>(s.actions.at(1).op);
    EXPECT_EQ(resect.seams.band_passes.rim_faces_in_region, passes.rim_faces_in_region);
    EXPECT_EQ(resect.seams.corner_turn_deg, seam_defaults(v).corner_turn_deg);
    EXPECT_EQ(resect.join.rigid_stages, join_defaults(v).rigid_stages);
    const auto& remesh = std::get<app::RemeshOp>(s.actions.at(2).op);
    EXPECT_EQ(remesh.passes.iterations, 5);
    EXPECT_EQ(remesh.passes.raise_angles_below_deg, passes.raise_angles_below_deg);
    EXPECT_EQ(remesh.passes.rim_faces_in_region, passes.rim_faces_in_region);
    const auto& join = std::get<app::JoinOp>(s.actions.at(3).op);
    EXPECT_EQ(join.seams.band_passes.rim_faces_in_region, passes.rim_faces_in_region);
    EXPECT_EQ(join.seams.band_width, seam_defaults(v).band_width);
    EXPECT_EQ(join.join.rigid_iterations, join_defaults(v).rigid_iterations);
    EXPECT_EQ(join.join.placement, engine::SuturePlacement::Mean);
    const auto& patch = std::get<app::PatchOp>(s.actions.at(4).op);
    EXPECT_EQ(patch.params.seam_passes.rim_faces_in_region, passes.rim_faces_in_region);
    EXPECT_EQ(patch.seams.corner_turn_deg, seam_defaults(v).corner_turn_deg);
    EXPECT_EQ(patch.join.pairing, join_defaults(v).pairing);
    const auto& incise = std::get<app::InciseOp>(s.actions.at(0).op);
    EXPECT_EQ(incise.params.repair_below_deg, incision_defaults(v).repair_below_deg);
    EXPECT_EQ(incise.params.repair_attempts, incision_defaults(v).repair_attempts);
    EXPECT_EQ(incise.params.band_passes.rim_faces_in_region,
              incision_defaults(v).band_passes.rim_faces_in_region);
    EXPECT_EQ(incise.params.band_width, 2.0);
    EXPECT_EQ(std::get<app::ResectOp>(s.actions.at(1).op).params.radius, 10.0);
  }
}

// A load's prepare starts from the version's settings, not the engine's; the op gives the edge
// length and the smoothing.
TEST(SessionDefaults, PrepareSettingsArePinnedPerVersion) {
  for (int v = 1; v <= app::kSessionFormatVersion; ++v) {
    SCOPED_TRACE(v);
    const engine::PrepareParams p = prepare_defaults(v);
    EXPECT_TRUE(p.clips.empty());
    EXPECT_FALSE(p.edge_length.has_value());
    EXPECT_FALSE(p.keep_caps);
    EXPECT_EQ(p.smoothing_iterations, 10);
    EXPECT_EQ(p.smoothing_bound, 0.02);
    EXPECT_EQ(p.remesh_iterations, 5);
    EXPECT_EQ(p.drop_area_fraction, 0.05);
    EXPECT_EQ(p.crease_angle_deg, 45.0);
    EXPECT_EQ(p.coarsen_in_halves_from, 200'000u);
    const app::Session s = parse_at(v, "{\"op\": \"load\", \"object\": \"a\", \"file\": \"a.stl\", "
                                       "\"prepare\": {\"edge_length\": 0.5, \"smoothing\": 3}}\n");
    const engine::PrepareParams& parsed = std::get<app::LoadOp>(s.actions.at(0).op).prepare->params;
    EXPECT_EQ(parsed.edge_length.value_or(0.0), 0.5);
    EXPECT_EQ(parsed.smoothing_iterations, 3);
    EXPECT_EQ(parsed.remesh_iterations, p.remesh_iterations);
    EXPECT_EQ(parsed.coarsen_in_halves_from, p.coarsen_in_halves_from);
  }
  EXPECT_THROW(prepare_defaults(app::kSessionFormatVersion + 1), std::invalid_argument);
}
