#include <gtest/gtest.h>

#include "sutura/ui/stage.hpp"

using namespace sutura::ui;

TEST(StageMachine, StartsInPlanWithoutMeshAndGatesEdits) {
  StageMachine m;
  EXPECT_EQ(m.stage(), Stage::Plan);
  EXPECT_TRUE(m.allowed(Command::OpenMesh));
  auto why = m.why_disabled(Command::Incise);
  ASSERT_TRUE(why.has_value());
  EXPECT_NE(why->find("Open a mesh"), std::string::npos);
  EXPECT_FALSE(m.allowed(Command::StartSimulation));
  EXPECT_THROW(m.simulation_started(), std::logic_error);
}

TEST(StageMachine, FullCycleAndContinuePlanning) {
  StageMachine m;
  m.mesh_loaded();
  EXPECT_TRUE(m.allowed(Command::Incise));
  EXPECT_TRUE(m.allowed(Command::Undo));
  EXPECT_FALSE(m.allowed(Command::ToggleBeforeAfter));
  m.simulation_started();
  EXPECT_EQ(m.stage(), Stage::Simulate);
  EXPECT_TRUE(m.allowed(Command::PauseResume));
  EXPECT_FALSE(m.allowed(Command::Incise));
  EXPECT_NE(m.why_disabled(Command::Suture)->find("simulation runs"), std::string::npos);
  m.simulation_finished();
  EXPECT_EQ(m.stage(), Stage::Inspect);
  EXPECT_TRUE(m.allowed(Command::MeasureCrossSection));
  EXPECT_TRUE(m.allowed(Command::SaveSnapshot));
  EXPECT_FALSE(m.allowed(Command::Incise));
  EXPECT_FALSE(m.allowed(Command::CancelSimulation));
  m.continue_planning();
  EXPECT_EQ(m.stage(), Stage::Plan);
  EXPECT_TRUE(m.allowed(Command::Incise));
}

TEST(StageMachine, CancelReturnsToPlan) {
  StageMachine m;
  m.mesh_loaded();
  m.simulation_started();
  m.simulation_cancelled();
  EXPECT_EQ(m.stage(), Stage::Plan);
  EXPECT_THROW(m.simulation_finished(), std::logic_error);
  EXPECT_THROW(m.simulation_cancelled(), std::logic_error);
}

TEST(StageMachine, EveryDisabledCommandExplainsWhy) {
  StageMachine m;
  for (int s = 0; s < 3; ++s) {
    int disabled = 0;  // every stage disables something (this loop is not vacuous)
    for (int a = 0; a <= static_cast<int>(Command::ContinuePlanning); ++a) {
      auto why = m.why_disabled(static_cast<Command>(a));
      if (why) {
        ++disabled;
        EXPECT_GT(why->size(), 10u) << to_string(static_cast<Command>(a));
      }
    }
    EXPECT_GT(disabled, 0) << "stage " << s;
    if (s == 0) { m.mesh_loaded(); m.simulation_started(); }
    else if (s == 1) m.simulation_finished();
  }
}
