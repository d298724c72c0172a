// A relaxation that fails says what to change (app::relaxation_advice): the collapse barrier,
// then the flap method, then the plan for collapsing elements; more increments when Newton
// does not converge; holding the object when the tangent is singular.
#include <gtest/gtest.h>

#include <string>

#include "replay_fixture.hpp"
#include "sutura/app/simulation.hpp"

using namespace sutura::app;
using sutura::engine::RelaxationSolver;

namespace {

const std::string kCollapsed =
    "relaxation failed at s = 0.72: static solve failed at load factor 1: every trial step "
    "collapsed a triangle (area below 0.01 of its rest area); rolled back to s = 0.7";

TEST(RelaxationAdvice, CollapsingElementsGetTheBarrierThenTheFlapMethodThenThePlan) {
  const std::string first = relaxation_advice(kCollapsed, false, RelaxationSolver::Static, 1.0);
  EXPECT_EQ(first.rfind("Advice: ", 0), 0u) << first;
  EXPECT_NE(first.find("\"collapse_barrier\": true"), std::string::npos) << first;
  EXPECT_NE(first.find("Resist collapse (gathered tissue)"), std::string::npos) << first;
  const std::string second = relaxation_advice(kCollapsed, true, RelaxationSolver::Static, 1.0);
  EXPECT_NE(second.find("\"solver\": \"dynamic\""), std::string::npos) << second;
  EXPECT_NE(second.find("Static, then damped dynamics (flap)"), std::string::npos) << second;
  // The flap method's static part (to s = 0.6) already is what the second advice proposes.
  const std::string flap_first = relaxation_advice(kCollapsed, true, RelaxationSolver::Static, 0.6);
  EXPECT_EQ(flap_first.find("Static, then damped dynamics (flap)"), std::string::npos) << flap_first;
  EXPECT_NE(flap_first.find("earlier"), std::string::npos) << flap_first;
  const std::string third = relaxation_advice(kCollapsed, true, RelaxationSolver::Dynamic, 1.0);
  EXPECT_NE(third.find("patch is wide enough"), std::string::npos) << third;
  EXPECT_NE(relaxation_advice("dynamics step 3 of 80 failed: the strain energy exploded (1e9 N*mm)",
                              true, RelaxationSolver::Dynamic, 1.0),
            "");
}

TEST(RelaxationAdvice, OtherFailuresGetTheirOwnAdviceOrNone) {
  EXPECT_NE(relaxation_advice("static solve failed at load factor 1: no convergence in 1 Newton "
                              "iterations",
                              false, RelaxationSolver::Static, 1.0)
                .find("\"steps\""),
            std::string::npos);
  EXPECT_NE(relaxation_advice("the tangent stiffness is singular (is the structure constrained?)",
                              false, RelaxationSolver::Static, 1.0)
                .find("Fix ends"),
            std::string::npos);
  EXPECT_EQ(relaxation_advice("the linear solve failed: out of memory", false, RelaxationSolver::Static, 1.0), "");
  // Dynamics' singular step matrix is not a missing hold.
  EXPECT_EQ(relaxation_advice("dynamics step 1 of 80 failed: the step matrix is singular", false,
                              RelaxationSolver::Dynamic, 1.0),
            "");
}

// Two strips 20 mm apart sutured and relaxed in one increment of one Newton iteration: the
// replay's error is the engine's message and the advice after it.
TEST(RelaxationAdvice, AFailedRelaxationInAReplaySaysWhatToChange) {
  const auto dir = sutura::testing::scratch_dir("advice", "strips");
  const std::string session =
      "{\"format\": \"sutura-session\", \"version\": 1}\n"
      "{\"op\": \"generate\", \"object\": \"s\", \"shape\": \"strip\", \"length\": 10.0, \"width\": 4.0, "
      "\"segments_length\": 10, \"segments_width\": 4}\n"
      "{\"op\": \"generate\", \"object\": \"s\", \"append\": true, \"shape\": \"strip\", \"length\": 10.0, "
      "\"width\": 4.0, \"segments_length\": 10, \"segments_width\": 6, \"translate\": [30.0, 0.0, 5.0]}\n"
      "{\"op\": \"material\", \"object\": \"s\", \"youngs_modulus\": 1.0, \"poisson_ratio\": 0.0, "
      "\"thickness\": 0.2}\n"
      "{\"op\": \"fix\", \"object\": \"s\", \"plane\": {\"point\": [0, 0, 0], \"normal\": [1, 0, 0]}}\n"
      "{\"op\": \"fix\", \"object\": \"s\", \"plane\": {\"point\": [40, 0, 5], \"normal\": [1, 0, 0]}}\n"
      "{\"op\": \"join\", \"object\": \"s\", \"chains\": [{\"from\": [10, -2, 0], \"to\": [10, 2, 0]}, "
      "{\"from\": [30, 2, 5], \"to\": [30, -2, 5]}]}\n"
      "{\"op\": \"simulate\", \"relax\": {\"steps\": 1, \"max_iterations\": 1}}\n";
  try {
    sutura::testing::replay_text(session, dir);
    FAIL() << "one Newton iteration cannot relax a 20 mm gap";
  } catch (const SessionError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.line(), 8);
    EXPECT_NE(m.find("relaxation failed at s = "), std::string::npos) << m;
    EXPECT_NE(m.find(". Advice: relax in more, smaller increments"), std::string::npos) << m;
  }
  std::filesystem::remove_all(dir);
}

// A static solve that ran off as Newton's iteration is advised the energy minimisation when
// its loads have a potential, and to hold the free rims first when they have none; nothing
// for a minimisation, nor for a message that names no such cause.
TEST(SolveAdvice, NewtonThatRunsOffIsAdvisedTheEnergyMinimisation) {
  const std::string exploded =
      "static solve failed at load factor 0.015625: the strain energy exploded (1.2e14 N*mm); "
      "rolled back to the last converged load factor 0";
  const std::string advice = solve_advice(exploded, false, true);
  EXPECT_EQ(advice.rfind("Advice: ", 0), 0u) << advice;
  EXPECT_NE(advice.find("\"minimize\": true"), std::string::npos) << advice;
  EXPECT_NE(solve_advice("static solve failed at load factor 1: no convergence in 30 Newton iterations",
                         false, true).find("\"minimize\": true"), std::string::npos);
  const std::string free_rim = solve_advice(exploded, false, false);
  EXPECT_NE(free_rim.find("hold that rim"), std::string::npos) << free_rim;
  EXPECT_TRUE(solve_advice(exploded, true, true).empty());
  EXPECT_TRUE(solve_advice("the tangent stiffness is singular", false, true).empty());
}

// A held, inflated tube solved with one Newton iteration cannot converge: the replay's error is
// the engine's message and the advice after it.
TEST(SolveAdvice, AFailedSolveInAReplaySaysWhatToChange) {
  const auto dir = sutura::testing::scratch_dir("advice", "solve");
  const std::string session =
      "{\"format\": \"sutura-session\", \"version\": 3}\n"
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
      "\"segments_around\": 16, \"segments_along\": 10}\n"
      "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 1.0, \"poisson_ratio\": 0.45, "
      "\"thickness\": 0.6}\n"
      "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
      "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n"
      "{\"op\": \"solve\", \"max_iterations\": 1}\n";
  try {
    sutura::testing::replay_text(session, dir);
    FAIL() << "one Newton iteration cannot inflate the tube to the tolerance";
  } catch (const SessionError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.line(), 6);
    EXPECT_NE(m.find("no convergence in"), std::string::npos) << m;
    EXPECT_NE(m.find(". Advice: solve as an energy minimisation (\"minimize\": true)"), std::string::npos) << m;
  }
  std::filesystem::remove_all(dir);
}

// A pressure has a potential energy unless it ends at a rim free to move: a tube's open ends
// until they are held, and a second object without loads changes nothing.
TEST(LoadsHavePotential, APressureEndingAtAFreeRimHasNone) {
  const auto dir = sutura::testing::scratch_dir("advice", "potential");
  const std::string start =
      "{\"format\": \"sutura-session\", \"version\": 3}\n"
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
      "\"segments_around\": 16, \"segments_along\": 10}\n"
      "{\"op\": \"generate\", \"object\": \"s\", \"shape\": \"strip\"}\n";
  const std::string pressure = "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n";
  const std::string hold = "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n";
  const Workspace unloaded = sutura::testing::replay_text(start, dir).workspace;
  EXPECT_TRUE(loads_have_potential(unloaded));
  const Workspace free_ends = sutura::testing::replay_text(start + pressure, dir).workspace;
  EXPECT_FALSE(loads_have_potential(free_ends));
  EXPECT_FALSE(loads_have_potential(free_ends, {"t"}));
  EXPECT_TRUE(loads_have_potential(free_ends, {"s"}));
  const Workspace held = sutura::testing::replay_text(start + hold + pressure, dir).workspace;
  EXPECT_TRUE(loads_have_potential(held));
  EXPECT_THROW((void)loads_have_potential(held, {"nothing"}), std::invalid_argument);
  // Once solved, the pressure is applied (a fixed load, no longer pending) and still judged:
  // with both ends held it has a potential, with one end free it has none.
  const std::string solve = "{\"op\": \"solve\", \"objects\": [\"t\"], \"load_steps\": 2}\n";
  const std::string hold_one = "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": [0]}\n";
  for (const bool both : {true, false}) {
    const Workspace solved =
        sutura::testing::replay_text(start + (both ? hold : hold_one) + pressure + solve, dir).workspace;
    ASSERT_TRUE(solved.find("t")->sim.pending_loads.pressures.empty());
    ASSERT_FALSE(solved.find("t")->sim.applied_loads.pressures.empty());
    EXPECT_EQ(loads_have_potential(solved), both);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
