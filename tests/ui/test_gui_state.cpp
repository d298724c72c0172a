// The window's state without a window: what the user is told after an edit.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../../ui/src/gui_state.hpp"
#include "controller_fixture.hpp"

using namespace sutura;
using nlohmann::json;

// An edit's warning stays on screen in red, labelled as a warning, until dismissed, not only
// in the plan step's details: here an incision drawn onto a strip's edge at 15 degrees, whose
// band keeps that corner (the report's warning names it).
TEST(GuiState, AnEditsWarningStaysOnScreen) {
  sutura::testing::ControllerFixture f("gui_state_warning");
  ui::GuiState s(*f.controller);
  ASSERT_TRUE(s.perform({{"op", "generate"}, {"object", "s"}, {"shape", "strip"}, {"length", 20.0},
                         {"width", 10.0}, {"segments_length", 20}, {"segments_width", 10}}));
  for (const auto& m : s.messages) EXPECT_FALSE(m.error) << m.text;
  json points = json::array();
  const double a = 15.0 * M_PI / 180.0;
  for (int i = 0; i <= 8; ++i) points.push_back({7.3 + i * std::cos(a), -5.0 + i * std::sin(a), 0.0});
  ASSERT_TRUE(s.perform({{"op", "incise"}, {"object", "s"}, {"points", points}}));
  bool shown = false;
  for (const auto& m : s.messages)
    shown = shown || (m.error && m.warning && m.text.find("the cut meets the open end at 15.0 degrees") == 0);
  EXPECT_TRUE(shown);
}
