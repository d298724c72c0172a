#include "script_player.hpp"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <fstream>

#include "gui_state.hpp"
#include "sutura/app/element_check.hpp"
#include "sutura/app/plan.hpp"

namespace sutura::ui {

using nlohmann::json;

namespace {

std::string last_error(const GuiState& s) {
  for (auto it = s.messages.rbegin(); it != s.messages.rend(); ++it)
    if (it->error) return " (the window shows: " + it->text + ")";
  return {};
}

}  // namespace

ScriptPlayer::ScriptPlayer(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("script " + file.string() + ": cannot be opened");
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      steps_.push_back(json::parse(line));
    } catch (const json::parse_error& e) {
      throw std::runtime_error("script " + file.string() + ":" + std::to_string(n) + ": " + e.what());
    }
    if (!steps_.back().is_object() || steps_.back().empty())
      throw std::runtime_error("script " + file.string() + ":" + std::to_string(n) +
                               ": each line must be a non-empty JSON object");
  }
}

void ScriptPlayer::fail(const std::string& why) {
  failure_ = "script step " + std::to_string(next_ + 1) + " " + steps_[next_].dump() + ": " + why;
}

bool ScriptPlayer::click_at(ScriptHost& host, float x, float y) {
  InputEvent e;
  switch (phase_++) {
    case 0:  // move, and let one frame see the pointer there (hover)
      e.kind = InputEvent::Kind::MouseMove;
      e.x = x;
      e.y = y;
      host.input.push(e);
      return false;
    case 1:
    case 2:
      e.kind = InputEvent::Kind::MouseButton;
      e.button = 0;
      e.pressed = phase_ == 2;
      host.input.push(e);
      released_ = std::chrono::steady_clock::now();
      return false;
    default:
      return true;  // the release frame has run
  }
}

void ScriptPlayer::step(ScriptHost& host, double frame_seconds) {
  while (!done()) {
    const json& s = steps_[next_];
    bool finished = true;  // the step completed this frame; go on with the next one
    bool yield = true;     // let a frame run before the next step
    try {
      if (s.contains("wait_frames")) {
        if (phase_++ == 0) frames_left_ = s["wait_frames"].get<int>();
        finished = frames_left_-- <= 0;
      } else if (s.contains("wait_idle")) {
        finished = !host.state.controller.busy();
      } else if (s.contains("move") || s.contains("move_world")) {
        std::array<float, 2> px{};
        if (s.contains("move")) {
          px = {s["move"][0].get<float>(), s["move"][1].get<float>()};
        } else {
          const auto& w = s["move_world"];
          if (!host.state.camera.project({w[0].get<double>(), w[1].get<double>(), w[2].get<double>()},
                                         host.width, host.height, px))
            return fail("the point is behind the camera");
          px[0] += host.view_left;
        }
        InputEvent e;
        e.kind = InputEvent::Kind::MouseMove;
        e.x = px[0];
        e.y = px[1];
        host.input.push(e);
      } else if (s.contains("scroll")) {
        InputEvent e;
        e.kind = InputEvent::Kind::Scroll;
        e.y = s["scroll"].get<double>();
        host.input.push(e);
      } else if (s.contains("click") || s.contains("click_world") || s.contains("click_widget")) {
        std::array<float, 2> px{};
        if (s.contains("click")) {
          px = {s["click"][0].get<float>(), s["click"][1].get<float>()};
        } else if (s.contains("click_world")) {
          const auto& w = s["click_world"];
          if (!host.state.camera.project({w[0].get<double>(), w[1].get<double>(), w[2].get<double>()},
                                         host.width, host.height, px))
            return fail("the point is behind the camera");
          px[0] += host.view_left;
        } else {
          const std::string label = s["click_widget"].get<std::string>();
          const auto c = host.state.widgets.centre(label);
          if (!c) return fail("no such widget on screen");
          if (phase_ == 0 && !host.state.widgets.visible(label)) {
            // Scrolled out of its window: scroll to it first, as a user would, then click.
            if (++scroll_frames_ > kMaxScrollFrames) return fail("the widget stays scrolled out of view");
            host.state.widgets.scroll_into_view(label);
            return;  // a frame draws the window scrolled
          }
          scroll_frames_ = 0;
          px = {c->x, c->y};
        }
        finished = click_at(host, px[0], px[1]);
        if (finished && s.value("timed", false)) {
          // From the release to this step: the frame that handled the click has been drawn
          // and presented, and the next one's events polled.
          std::printf("click response %.1f ms\n",
                      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - released_).count());
          std::fflush(stdout);
        }
      } else if (s.contains("key")) {
        static const std::map<std::string, int> kKeys = {
            {"enter", GLFW_KEY_ENTER}, {"escape", GLFW_KEY_ESCAPE}, {"f", GLFW_KEY_F},
            {"z", GLFW_KEY_Z},         {"y", GLFW_KEY_Y},         {"end", GLFW_KEY_END}};
        const auto it = kKeys.find(s["key"].get<std::string>());
        if (it == kKeys.end()) return fail("unknown key");
        const bool ctrl = s.value("ctrl", false);
        const auto key_event = [&](int key, bool pressed) {
          InputEvent e;
          e.kind = InputEvent::Kind::Key;
          e.key = key;
          e.pressed = pressed;
          e.mods = ctrl ? GLFW_MOD_CONTROL : 0;
          host.input.push(e);
        };
        if (ctrl) key_event(GLFW_KEY_LEFT_CONTROL, true);
        key_event(it->second, true);
        key_event(it->second, false);
        if (ctrl) key_event(GLFW_KEY_LEFT_CONTROL, false);
      } else if (s.contains("type")) {
        for (unsigned char c : s["type"].get<std::string>()) {
          InputEvent e;
          e.kind = InputEvent::Kind::Char;
          e.codepoint = c;
          host.input.push(e);
        }
      } else if (s.contains("screenshot")) {
        host.screenshot(s["screenshot"].get<std::string>());
      } else if (s.contains("expect")) {
        const json& x = s["expect"];
        if (x.contains("objects") && !host.state.controller.busy() &&
            host.state.controller.workspace().objects().size() != x["objects"].get<std::size_t>())
          return fail("there are " + std::to_string(host.state.controller.workspace().objects().size()) +
                      " objects");
        if (x.value("no_errors", false))
          for (const auto& m : host.state.messages)
            if (m.error) return fail("the window shows an error: " + m.text);
        if (x.contains("message_contains")) {
          const std::string want = x["message_contains"].get<std::string>();
          bool found = false;
          for (const auto& m : host.state.messages) found = found || m.text.find(want) != std::string::npos;
          if (!found) return fail("no message contains \"" + want + "\"");
        }
        if (x.contains("message_not_contains")) {
          const std::string unwanted = x["message_not_contains"].get<std::string>();
          for (const auto& m : host.state.messages)
            if (m.text.find(unwanted) != std::string::npos) return fail("a message says: " + m.text);
        }
        if ((x.contains("plan_applied") || x.contains("plan_contains")) && host.state.controller.busy())
          return fail("the plan is read when no op runs: wait_idle first");
        if (x.contains("plan_applied")) {
          const app::Plan plan = host.state.controller.plan();
          if (plan.applied != x["plan_applied"].get<std::size_t>())
            return fail("the plan has " + std::to_string(plan.applied) + " steps in effect");
        }
        if (x.contains("plan_contains")) {
          const std::string want = x["plan_contains"].get<std::string>();
          bool found = false;
          for (const auto& step : host.state.controller.plan().steps)
            found = found || app::describe_action(step.source).find(want) != std::string::npos;
          if (!found) return fail("no plan step reads \"" + want + "\"");
        }
        if (x.contains("view")) {
          const std::optional<StandardView> v = host.state.camera.standard_view();
          const std::string seen = v ? to_string(*v) : "no standard view";
          if (seen != x["view"].get<std::string>()) return fail("the camera looks from " + seen);
        }
        if (x.contains("min_angle_deg")) {
          if (host.state.controller.busy()) return fail("angles are read when no op runs: wait_idle first");
          for (const auto& a : app::smallest_angles(host.state.controller.workspace()))
            if (a.degrees < x["min_angle_deg"].get<double>())
              return fail("'" + a.object + "' has an angle of " + std::to_string(a.degrees) + " degrees");
        }
        if (x.contains("stage") &&
            x["stage"].get<std::string>() != std::string(to_string(host.state.stages.stage())))
          return fail("stage is " + std::string(to_string(host.state.stages.stage())) +
                      last_error(host.state));
        yield = false;
      } else if (s.contains("time_frames")) {
        if (phase_ == 0) {
          frames_left_ = s["time_frames"].get<int>();
          timed_seconds_ = 0.0;
        } else {
          timed_seconds_ += frame_seconds;
        }
        finished = phase_++ > 0 && --frames_left_ <= 0;
        if (finished) {
          const int n = s["time_frames"].get<int>();
          std::printf("frames %d  mean frame time %.2f ms  (%.1f fps)\n", n,
                      1e3 * timed_seconds_ / n, n / timed_seconds_);
          std::fflush(stdout);
        }
      } else if (s.contains("quit")) {
        host.state.quit_requested = true;  // as closing the window: asks first if work would be lost
      } else {
        return fail("unknown step");
      }
    } catch (const json::exception& e) {
      return fail(e.what());
    }
    if (!finished) return;
    ++next_;
    phase_ = 0;
    if (yield) return;
  }
}

}  // namespace sutura::ui
