// run_gui: window, ImGui and the frame loop.
#include "sutura/ui/gui.hpp"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <utility>

#include "gui_state.hpp"
#include "input_events.hpp"
#include "keep_angle.hpp"
#include "panels.hpp"
#include "script_player.hpp"
#include "sutura/app/element_check.hpp"
#include "sutura/app/output_paths.hpp"
#include "sutura/app/session.hpp"
#include "sutura/render/glfw_library.hpp"
#include "sutura/render/renderer.hpp"
#include "viewport.hpp"

namespace sutura::ui {

namespace fs = std::filesystem;

namespace {

// A new recording in out_dir: session-<time>.jsonl, or session-<time>-2.jsonl, ... when
// another window started in the same second (files are created exclusively: none is shared or
// replaced); `start(file)` creates it.
template <class Start>
SessionRecorder record_new_session(const fs::path& out_dir, const Start& start) {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  for (int k = 1;; ++k) {
    std::string name = "session-";
    name += stamp;
    if (k > 1) name += '-', name += std::to_string(k);
    const fs::path file = out_dir / (name + ".jsonl");
    if (fs::exists(file) && k < 1000) continue;
    try {
      return start(file);
    } catch (const std::runtime_error&) {
      if (!fs::exists(file) || k >= 1000) throw;  // not a race lost to another window
    }
  }
}

std::array<render::Point3, 2> bounds_of(const std::vector<app::ObjectView>& objects) {
  render::Scene scene;
  for (const auto& a : objects) app::add_plan_surfaces(scene, a.positions, {}, a.plan, a.color, false);
  return render::scene_bounds(scene);
}

// Framebuffer column of window x coordinate `x` (window `width`, framebuffer `fb_width` pixels
// wide), within the framebuffer.
int framebuffer_x(float x, int width, int fb_width) {
  return std::clamp(int(x * float(fb_width) / float(width)), 0, fb_width - 1);
}

// Worker results change the stage: finished -> Inspect, failed or cancelled -> Plan. (A
// failed keep-angle run is taken back and tried once more, wider; a cancelled one, or a second
// failure, is taken back and ends in Inspect: keep_angle.hpp.)
void finish_worker(GuiState& s) {
  const auto outcome = s.controller.poll();
  if (!outcome) return;
  // A cancel that came after the run ended, before this poll, still stops the plan.
  if (outcome->ok && !s.queued_runs.empty() && s.controller.cancel_requested()) {
    s.keep_angle_after_run = false;
    if (s.keeping_angle) return take_back_keep_angle(s, "the remesh of small angles was cancelled");
    s.queued_runs.clear();
    s.stages.simulation_finished();
    s.info(outcome->op + " finished; the next run was cancelled before it started");
    return;
  }
  if (outcome->ok && !s.queued_runs.empty()) {
    // The next phase starts in this same frame: the run never looks idle in between.
    const nlohmann::json next = s.queued_runs.front();
    s.queued_runs.pop_front();
    std::string why;
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", outcome->details.value("seconds", 0.0));
    if (s.start_run(next, s.run + 1, s.runs, why)) {
      std::string text = outcome->op + " phase finished in " + seconds + " s";
      const nlohmann::json& d = outcome->details;
      if (d.contains("summary") && d["summary"].is_string()) text += ": " + d["summary"].get<std::string>();
      s.info(text + "; the next phase is running");
      return;
    }
    s.keep_angle_after_run = false;
    if (s.keeping_angle) return take_back_keep_angle(s, "the next run of the remesh of small angles could not start: " + why);
    s.queued_runs.clear();
    s.stages.simulation_cancelled();
    s.error(outcome->op + ": the next phase could not start: " + why);
    return;
  }
  s.queued_runs.clear();
  if (outcome->ok && std::exchange(s.keep_angle_after_run, false) && !s.controller.cancel_requested() &&
      start_keep_angle(s, *outcome))
    return;
  if (outcome->ok) {
    s.stages.simulation_finished();
    const nlohmann::json& d = outcome->details;
    s.last_equilibrium = d.value("equilibrium", nlohmann::json());
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2f", d.value("seconds", 0.0));
    std::string text = outcome->op + " finished in " + seconds + " s";
    if (d.contains("summary") && d["summary"].is_string()) text += ": " + d["summary"].get<std::string>();  // design_patch
    if (s.last_equilibrium.is_object() && s.last_equilibrium.value("stable", false))
      text += "; the relaxed shape is a stable equilibrium";
    if (outcome->op == "simulate" || outcome->op == "solve") {
      // The quality of the shape shown, which the keep-angle step looks after.
      if (const auto worst = app::worst_angle(app::smallest_angles(s.controller.workspace()))) {
        char degrees[32];
        std::snprintf(degrees, sizeof degrees, "%.1f", worst->degrees);
        text += "; smallest angle ";
        text += degrees;
        text += " degrees ('";
        text += worst->object;
        text += "')";
      }
    }
    const std::optional<std::string> still_below = s.keeping_angle ? still_below_warning(s) : std::nullopt;
    s.keeping_angle = false;
    s.info(text);
    if (still_below) s.warn(*still_below);
    // An unstable end state stays on screen until dismissed, like an error.
    if (d.contains("warning")) s.warn(d["warning"].get<std::string>());
    return;
  }
  s.keep_angle_after_run = false;
  if (s.keeping_angle && outcome->cancelled)
    return take_back_keep_angle(s, "its " + outcome->op + " was cancelled");
  if (s.keeping_angle) {
    retry_keep_angle_wider(s, *outcome);
    return;
  }
  s.stages.simulation_cancelled();
  if (outcome->cancelled) s.info(outcome->op + " cancelled: the state before the run is restored");
  else s.error(outcome->op + " failed (state before the run restored): " + outcome->message);
}

// View caches and picking structures follow the workspace (or the live run).
void refresh_view(GuiState& s, float aspect) {
  if (s.controller.busy()) {
    s.view.apply_live(s.controller.progress());
    return;
  }
  const auto field = s.stages.stage() == Stage::Inspect ? s.field : ViewField::None;
  s.view.update(s.controller.workspace(), s.controller.revision(), field);
  if (s.picker_revision != s.controller.revision()) {
    std::vector<const engine::SurfaceMesh*> meshes;
    for (const auto& o : s.controller.workspace().objects()) meshes.push_back(&o.mesh);
    s.picker.rebuild(meshes);
    s.picker_revision = s.controller.revision();
    s.end_labels.clear();
    for (const auto& o : s.controller.workspace().objects())
      for (const auto& loop : o.mesh.boundary_loops())
        if (std::string name = app::end_name(o, loop); !name.empty())
          s.end_labels.emplace_back(app::loop_centroid(o.mesh, loop), std::move(name));
  }
  if (!s.controller.busy() && s.element_check_revision != s.controller.revision()) {
    s.element_check = app::check_elements(s.controller.workspace());
    s.smallest_angles = app::smallest_angles(s.controller.workspace());
    s.element_check_revision = s.controller.revision();
  }
  if (s.fit_requested && !s.view.current().empty()) {
    s.camera.fit(bounds_of(s.view.current()), aspect);
    s.fit_requested = false;
  }
  if (s.view_requested) {
    s.camera.look_from(*s.view_requested);
    s.view_requested.reset();
  }
}

// Draws the 3-D view into framebuffer columns [x0, x0 + width); columns left of it (under
// the workflow window) are cleared to the background colour.
void draw_view(GuiState& s, render::Renderer& renderer, int x0, int width, int height) {
  const Overlays overlays = viewport_overlays(s);
  const bool inspect = s.stages.stage() == Stage::Inspect;
  const auto cmap = inspect ? s.view.color_map() : std::nullopt;
  const render::Camera camera = s.shown_camera();
  if (x0 > 0) renderer.draw(make_scene({}, {}, std::nullopt, false), camera, x0, height);
  const std::optional<render::ClipPlane> clip = s.clip_plane();
  const auto scene = [&](const std::vector<app::ObjectView>& objects, const Overlays& on_top) {
    render::Scene scene = make_scene(objects, on_top, cmap, s.wireframe);
    scene.clip = clip;
    return scene;
  };
  if (inspect && s.side_by_side) {
    const render::Camera& wide = camera;
    const int half = width / 2;
    render::RenderOptions left, right;
    left.viewport_x = x0;
    left.draw_legend = false;  // one legend (on the right) serves both views
    left.legend_space = true;  // both halves frame the scene alike, as the snapshot does
    right.viewport_x = x0 + half;
    renderer.draw(scene(s.view.before(), {}), wide, half, height, left);
    renderer.draw(scene(s.view.current(), overlays), wide, width - half, height, right);
    return;
  }
  const bool before = inspect && s.show_before;
  render::RenderOptions options;
  options.viewport_x = x0;
  renderer.draw(scene(before ? s.view.before() : s.view.current(), before ? Overlays{} : overlays),
                camera, width, height, options);
}

// The names of the open ends (root, descending, innominate...) beside them while planning.
void end_labels(const GuiState& s) {
  if (s.stages.stage() != Stage::Plan || s.controller.busy()) return;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  std::vector<std::array<float, 4>> placed;  // x0, y0, x1, y1 of the labels drawn so far
  const std::optional<render::ClipPlane> clip = s.clip_plane();
  for (const auto& [where, name] : s.end_labels) {
    if (clip) {  // no label for an end that Cut open has cut away
      const auto& n = clip->normal;
      const auto& p = clip->point;
      if (n[0] * (where.x() - p[0]) + n[1] * (where.y() - p[1]) + n[2] * (where.z() - p[2]) > 0.0) continue;
    }
    std::array<float, 2> px{};
    if (!s.camera.project(where, s.scene_width, s.view_height, px)) continue;
    ImVec2 at(s.view_left + px[0] + 10.0f, px[1] - 8.0f);
    const ImVec2 size = ImGui::CalcTextSize(name.c_str());
    // Below any label it would cover (ends close together on the screen).
    for (bool moved = true; moved;) {
      moved = false;
      for (const auto& r : placed)
        if (at.x < r[2] && at.x + size.x > r[0] && at.y < r[3] && at.y + size.y > r[1]) {
          at.y = r[3] + 2.0f;
          moved = true;
        }
    }
    placed.push_back({at.x - 3.0f, at.y - 1.0f, at.x + size.x + 3.0f, at.y + size.y + 1.0f});
    draw->AddRectFilled(ImVec2(at.x - 3.0f, at.y - 1.0f), ImVec2(at.x + size.x + 3.0f, at.y + size.y + 1.0f),
                        IM_COL32(255, 255, 255, 200), 3.0f);
    draw->AddText(at, IM_COL32(60, 40, 20, 255), name.c_str());
  }
}

// "Before" / "After" over the views of the Inspect stage.
void view_captions(const GuiState& s, float view_width) {
  if (s.stages.stage() != Stage::Inspect) return;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const float y = ImGui::GetFrameHeight() + 8.0f;
  const ImU32 colour = IM_COL32(40, 40, 40, 255);
  const float left = s.view_left + kViewCubeCorner + 4.0f;  // right of the view cube
  if (s.side_by_side) {
    draw->AddText(ImVec2(left, y), colour, "Before");
    draw->AddText(ImVec2(s.view_left + 0.5f * view_width + 12.0f, y), colour, "After");
  } else {
    draw->AddText(ImVec2(left, y), colour, s.show_before ? "Before" : "After");
  }
}

// A controller for a window on `session` (empty: none): recording to `record` (empty: a new
// file in the output directory), which starts as a copy of the session and continues it; the
// session itself is never written. Throws when the session cannot be read or replayed (the
// new recording then holds the copy).
std::unique_ptr<SessionController> open_controller(const GuiOptions& options, const fs::path& session,
                                                   const fs::path& record) {
  std::optional<app::Session> existing;
  if (!session.empty()) existing = app::load_session(session);
  const auto start = [&](const fs::path& file) {
    return existing ? SessionRecorder::continue_in(session, file)
                    : SessionRecorder::create(file, "recorded by sutura gui");
  };
  SessionRecorder recorder = record.empty() ? record_new_session(options.out_dir, start) : start(record);
  app::ReplayOptions replay_options;
  replay_options.out_dir = options.out_dir;
  if (existing) replay_options.protected_inputs.push_back(session);
  replay_options.threads = options.threads;
  auto controller = std::make_unique<SessionController>(std::move(recorder), replay_options);
  if (existing) controller->replay_existing(*existing);
  return controller;
}

// Ends what `controller` runs and writes its report.json.
void close_controller(SessionController& controller) {
  if (controller.busy()) controller.cancel();
  while (controller.busy() && !controller.poll()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  try {
    controller.write_report();
  } catch (const std::exception& e) {
    std::cerr << "sutura: error: writing the report: " << e.what() << "\n";
  }
}

void start_session(GuiState& s) {
  if (!s.controller.workspace().objects().empty()) s.stages.mesh_loaded();
  s.info("Recording to " + s.controller.recorder().file().string());
}

}  // namespace

int run_gui(const GuiOptions& options) {
  std::unique_ptr<SessionController> controller;
  try {
    controller = open_controller(options, options.session, options.record);
  } catch (const std::exception& e) {
    std::cerr << "sutura: error: " << e.what() << "\n";
    return 1;
  }
  std::optional<ScriptPlayer> script;
  if (!options.script.empty()) script.emplace(options.script);

  render::WindowContext window(options.width, options.height, "Sutura", options.visible,
                               options.samples);
  auto* window_handle = static_cast<GLFWwindow*>(window.native_window());
  const render::GlfwLibrary& glfw = render::glfw();  // resolved when the window opened
  render::Renderer renderer(window);
  glfw.swap_interval(0);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to the user's files
  // Windows resize from their edges (the message history from its top edge), with the
  // matching mouse cursors (GLFW's standard ones; the diagonal and all-way shapes fall back to
  // the arrow).
  io.ConfigWindowsResizeFromEdges = true;
  io.BackendFlags |= ImGuiBackendFlags_HasMouseCursors;
  std::array<GLFWcursor*, ImGuiMouseCursor_COUNT> cursors{};
  cursors[ImGuiMouseCursor_TextInput] = glfw.create_standard_cursor(GLFW_IBEAM_CURSOR);
  cursors[ImGuiMouseCursor_ResizeNS] = glfw.create_standard_cursor(GLFW_VRESIZE_CURSOR);
  cursors[ImGuiMouseCursor_ResizeEW] = glfw.create_standard_cursor(GLFW_HRESIZE_CURSOR);
  cursors[ImGuiMouseCursor_Hand] = glfw.create_standard_cursor(GLFW_HAND_CURSOR);
  ImGuiMouseCursor shown_cursor = ImGuiMouseCursor_Arrow;
  map_imgui_keys();
  ImGui::StyleColorsLight();
  window.make_current();
  ImGui_ImplOpenGL3_Init("#version 330");

  InputQueue input;
  input.attach(window_handle);
  std::optional<GuiState> state;
  state.emplace(*controller);
  start_session(*state);

  std::optional<fs::path> screenshot_to;
  int exit_code = 0;
  int script_quit_frames = 0;
  auto last = std::chrono::steady_clock::now();
  double frame_seconds = 0.0;
  int idle_frames = 0;
  std::uint64_t news_drawn = controller->news();
  while (!state->quit) {
    // File > Open session, confirmed: a run going on is cancelled (as quitting cancels it), a
    // frame says what is happening (the replay blocks the window), and then the window goes on
    // with the other session; when it cannot be opened, with this one.
    if (state->open_requested && state->open_confirmed) {
      if (controller->busy()) {
        state->queued_runs.clear();
        state->keep_angle_after_run = false;
        controller->cancel();
        while (controller->busy() && !controller->poll()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
        // A remesh of small angles whose settle was cancelled is taken back, in this session's
        // recording, before it is left.
        if (state->keeping_angle) take_back_keep_angle(*state, "the settle was cancelled to open another session");
        else state->stages.simulation_cancelled();
        state->info("The running simulation was cancelled to open another session");
      }
      if (!state->open_announced) {
        state->open_announced = true;
        state->info("Opening " + state->open_requested->string() + ": replaying its actions");
      } else {
        const fs::path file = *state->open_requested;
        state->open_requested.reset();
        state->open_confirmed = false;
        state->open_announced = false;
        try {
          auto next = open_controller(options, file, {});
          close_controller(*controller);
          // The window goes on: its message history and where its widgets were drawn (a
          // script's click in progress looks there) carry over; the rest is the new session's.
          WidgetRegistry widgets = std::move(state->widgets);
          std::deque<Message> messages = std::move(state->messages);
          state.reset();
          controller = std::move(next);
          state.emplace(*controller);
          state->widgets = std::move(widgets);
          state->messages = std::move(messages);
          state->info("Opened " + file.string());
          start_session(*state);
          news_drawn = controller->news();
        } catch (const std::exception& e) {
          state->error("Open session: " + std::string(e.what()));
        }
        // A controller destroyed here (the old one, or the new one that failed) may have
        // made its snapshot renderer's OSMesa context current on this thread as it went.
        window.make_current();
      }
    }
    GuiState& s = *state;
    // Draw continuously only while something happens: a running op gets the CPU (the view
    // follows it at up to 10 frames per second), an idle window waits for input.
    if (controller->busy()) glfw.wait_events_timeout(0.1);
    else if (script) glfw.poll_events();
    else if (idle_frames > 3) glfw.wait_events_timeout(0.5);
    else glfw.poll_events();
    idle_frames = input.empty() ? idle_frames + 1 : 0;
    if (glfw.window_should_close(window_handle)) {  // the window's close button: ask first if work would be lost
      glfw.set_window_should_close(window_handle, GLFW_FALSE);
      s.quit_requested = true;
      if (s.unsaved_work().empty()) s.quit = true;  // also when minimised (no frame to ask in)
    }
    // While an op runs, a frame is drawn only when there is something new to show (input,
    // the run's progress or shape, its end) or every half second (the time and estimate).
    if (controller->busy() && input.empty() && controller->news() == news_drawn &&
        std::chrono::steady_clock::now() - last < std::chrono::milliseconds(500) &&
        (!script || script->waiting_for_idle()))
      continue;
    news_drawn = controller->news();
    int width = 0, height = 0, fb_width = 0, fb_height = 0;
    glfw.get_window_size(window_handle, &width, &height);
    glfw.get_framebuffer_size(window_handle, &fb_width, &fb_height);
    if (width <= 0 || height <= 0 || fb_width <= 0 || fb_height <= 0) continue;  // minimised
    if (script) {
      // The part of the view the scene is drawn in (left of a legend), as picking sees it.
      ScriptHost host{input, s, s.view_left, s.scene_width, float(height),
                      [&](const fs::path& p) { screenshot_to = p; }};
      script->step(host, frame_seconds);
      if (script->failure()) {
        std::cerr << "sutura: " << *script->failure() << "\n";
        exit_code = 3;
        break;
      }
      // A script that ended asking to quit, while the window still waits (an unanswered
      // quit dialog), fails instead of spinning until a test's timeout.
      script_quit_frames = script->done() && s.quit_requested ? script_quit_frames + 1 : 0;
      if (script_quit_frames > 100) {
        std::cerr << "sutura: the script ended but the window did not quit (a dialog is waiting)\n";
        exit_code = 3;
        break;
      }
    }
    input.feed_imgui();
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DisplayFramebufferScale = ImVec2(float(fb_width) / width, float(fb_height) / height);
    const auto now = std::chrono::steady_clock::now();
    frame_seconds = std::chrono::duration<double>(now - last).count();
    last = now;
    io.DeltaTime = float(std::max(frame_seconds, 1e-4));

    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    s.widgets.new_frame();
    try {
      finish_worker(s);
      menu_bar(s);
      quit_dialog(s);
      open_dialog(s);
      s.section_controls_open = false;  // set again by the Inspect panel while they show
      workflow_window(s);
      message_window(s);
      const float view_width = std::max(1.0f, float(width) - s.view_left);
      s.view_width = view_width;
      s.view_height = float(height);
      // With a legend the single view is drawn left of its column (render::legend_width), so
      // camera fits and picking rays take that part. The renderer lays the legend out in
      // framebuffer pixels (its font scale steps with the height): the column is measured
      // there and brought back to window pixels.
      float scene_width = view_width;
      if (s.stages.stage() == Stage::Inspect && !s.side_by_side) {
        render::Scene legend_only;
        legend_only.color_map = s.view.color_map();
        const int x0 = framebuffer_x(s.view_left, width, fb_width);
        const int column = render::legend_width(legend_only, fb_width - x0, fb_height);
        scene_width = std::max(1.0f, view_width - float(column) * float(width) / float(fb_width));
      }
      s.scene_width = scene_width;
      refresh_view(s, scene_width / float(height));
      viewport_input(s, std::max(1.0f, scene_width), float(height));
      view_captions(s, view_width);
      end_labels(s);
      view_cube(s);
    } catch (const std::exception& e) {
      s.error(e.what());
    }
    ImGui::Render();
    if (const ImGuiMouseCursor want = ImGui::GetMouseCursor(); want != shown_cursor) {
      shown_cursor = want;
      glfw.set_cursor(window_handle, want >= 0 && want < ImGuiMouseCursor_COUNT ? cursors[std::size_t(want)] : nullptr);
    }

    try {
      const int x0 = framebuffer_x(s.view_left, width, fb_width);
      draw_view(s, renderer, x0, fb_width - x0, fb_height);
    } catch (const std::exception& e) {
      s.error(std::string("drawing the view: ") + e.what());
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (screenshot_to) {
      try {
        const auto png = render::encode_png(renderer.read_framebuffer(fb_width, fb_height));
        if (screenshot_to->has_parent_path()) fs::create_directories(screenshot_to->parent_path());
        app::write_file_atomically(*screenshot_to, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
        s.info("Window saved to " + screenshot_to->string());
      } catch (const std::exception& e) {
        s.error(std::string("window screenshot: ") + e.what());
      }
      screenshot_to.reset();
    }
    glfw.swap_buffers(window_handle);
  }
  // The step in progress may be the click that quit ("Quit anyway"); any later one never ran.
  if (script && exit_code == 0 && script->steps_left() > 1) {
    std::cerr << "sutura: the window quit before the script ended\n";
    exit_code = 3;
  }
  glfw.set_cursor(window_handle, nullptr);
  for (GLFWcursor* c : cursors)
    if (c) glfw.destroy_cursor(c);
  close_controller(*controller);
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
  return exit_code;
}

}  // namespace sutura::ui
