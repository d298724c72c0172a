// The Simulate panel's progress: a relaxation measured by s (its step count is re-planned as
// increments halve), an estimate from the pace so far once there is one to speak of, and the
// settling step said to be last.
#include <gtest/gtest.h>

#include "../../ui/src/progress_text.hpp"

using sutura::ui::LiveProgress;
using sutura::ui::progress_text;

TEST(ProgressText, ARelaxationIsMeasuredBySAndEstimatedFromItsPace) {
  LiveProgress p;
  p.phase = "relax";
  p.s = 0.4;
  p.step = 2;
  p.steps = 9;  // re-planned: would make the bar jump
  p.fraction = 2.0 / 9.0;
  const auto t = progress_text(p, 12.0, 0.0, 1, 1);
  EXPECT_DOUBLE_EQ(t.fraction, 0.4);
  EXPECT_EQ(t.bar, "Relaxing the rest shape: s = 0.40 of 1");
  EXPECT_EQ(t.detail, "12 s so far, about 18 s left before settling");  // 12 s for 0.4: 18 s for 0.6
  // Continued from s = 0.6 (the flap's second run): the bar covers [0.6, 1].
  p.s = 0.8;
  const auto second = progress_text(p, 30.0, 0.6, 2, 2);
  EXPECT_DOUBLE_EQ(second.fraction, 0.5);
  EXPECT_EQ(second.detail, "30 s so far, about 30 s left before settling (run 2 of 2)");
}

TEST(ProgressText, NoEstimateTooEarlyNorWhileSettling) {
  LiveProgress p;
  p.phase = "relax";
  p.s = 0.02;
  EXPECT_EQ(progress_text(p, 5.0, 0.0, 1, 1).detail, "5 s so far");  // 2 % of the way
  p.s = 0.5;
  EXPECT_EQ(progress_text(p, 1.0, 0.0, 1, 1).detail, "1 s so far");  // under 2 s
  p.phase = "settle";
  p.s = 1.0;
  const auto t = progress_text(p, 75.0, 0.0, 1, 1);
  EXPECT_EQ(t.bar, "Settling to equilibrium (last step): s = 1.00 of 1");
  EXPECT_EQ(t.detail, "1 min 15 s so far; settling takes as long as the shape needs");
}

TEST(ProgressText, PlainDynamicsCountsSteps) {
  LiveProgress p;
  p.phase = "simulate";
  p.step = 30;
  p.steps = 60;
  p.fraction = 0.5;
  p.paused = true;
  const auto t = progress_text(p, 10.0, std::nullopt, 1, 1);
  EXPECT_DOUBLE_EQ(t.fraction, 0.5);
  EXPECT_EQ(t.bar, "Simulating: step 30 of 60  (paused)");
  EXPECT_EQ(t.detail, "10 s so far, about 10 s left");
  LiveProgress starting;
  EXPECT_EQ(progress_text(starting, 0.2, std::nullopt, 1, 1).bar,
            "Starting (assembling and factorising the first tangent)");
}
