// The Simulate panel's progress: a relaxation measured by s over its range (its step count is
// re-planned as increments halve; its first report comes after the first increment), an
// estimate from the pace so far once there is one to speak of, and the settling step said to
// be last.
#include <gtest/gtest.h>

#include "../../ui/src/progress_text.hpp"

using sutura::ui::LiveProgress;
using sutura::ui::progress_text;

namespace {

LiveProgress relaxing(double s, double s_start, double s_end) {
  LiveProgress p;
  p.phase = "relax";
  p.s = s;
  p.s_start = s_start;
  p.s_end = s_end;
  return p;
}

}  // namespace

TEST(ProgressText, ARelaxationIsMeasuredBySOverItsRange) {
  // The GUI's default: 3 increments from s = 0, the first report at s = 1/3 after 4 s.
  LiveProgress p = relaxing(1.0 / 3.0, 0.0, 1.0);
  p.step = 1;
  p.steps = 9;  // re-planned: would make the bar jump
  p.fraction = 1.0 / 9.0;
  auto t = progress_text(p, 4.0, 1, 1);
  EXPECT_DOUBLE_EQ(t.fraction, 1.0 / 3.0);
  EXPECT_EQ(t.bar, "Relaxing the rest shape: s = 0.33 (to 1.00)");
  EXPECT_EQ(t.detail, "4 s so far, about 8 s left before settling");
  // The flap's first run stops at until = 0.6: full at 0.6, estimated towards 0.6.
  t = progress_text(relaxing(0.3, 0.0, 0.6), 10.0, 1, 2);
  EXPECT_DOUBLE_EQ(t.fraction, 0.5);
  EXPECT_EQ(t.detail, "10 s so far, about 10 s left (run 1 of 2)");
  EXPECT_DOUBLE_EQ(progress_text(relaxing(0.6, 0.0, 0.6), 20.0, 1, 2).fraction, 1.0);
  // Its second run continues from 0.6 to 1.
  t = progress_text(relaxing(0.8, 0.6, 1.0), 30.0, 2, 2);
  EXPECT_DOUBLE_EQ(t.fraction, 0.5);
  EXPECT_EQ(t.detail, "30 s so far, about 30 s left before settling (run 2 of 2)");
}

TEST(ProgressText, NoEstimateTooEarlyNorWhileSettling) {
  EXPECT_EQ(progress_text(relaxing(0.02, 0.0, 1.0), 5.0, 1, 1).detail, "5 s so far");  // 2 % of the way
  EXPECT_EQ(progress_text(relaxing(0.5, 0.0, 1.0), 1.0, 1, 1).detail, "1 s so far");   // under 2 s
  LiveProgress p = relaxing(1.0, 0.0, 1.0);
  p.phase = "settle";
  const auto t = progress_text(p, 75.0, 1, 1);
  EXPECT_EQ(t.bar, "Settling to equilibrium (last step): s = 1.00 (to 1.00)");
  EXPECT_EQ(t.detail, "1 min 15 s so far; settling takes as long as the shape needs");
}

TEST(ProgressText, TimesAreRoundedBeforeTheyAreSplit) {
  EXPECT_EQ(progress_text(relaxing(0.01, 0.0, 1.0), 119.6, 1, 1).detail, "2 min 00 s so far");
  EXPECT_EQ(progress_text(relaxing(0.01, 0.0, 1.0), 59.6, 1, 1).detail, "1 min 00 s so far");
  EXPECT_EQ(progress_text(relaxing(0.01, 0.0, 1.0), 0.2, 1, 1).detail, "1 s so far");
}

TEST(ProgressText, PlainDynamicsCountsSteps) {
  LiveProgress p;
  p.phase = "simulate";
  p.step = 30;
  p.steps = 60;
  p.fraction = 0.5;
  p.paused = true;
  const auto t = progress_text(p, 10.0, 1, 1);
  EXPECT_DOUBLE_EQ(t.fraction, 0.5);
  EXPECT_EQ(t.bar, "Simulating: step 30 of 60  (paused)");
  EXPECT_EQ(t.detail, "10 s so far, about 10 s left");
  EXPECT_EQ(progress_text(LiveProgress{}, 0.2, 1, 1).bar, "Starting (assembling and factorising the first tangent)");
}
