// sutura — command-line entry point. Subcommands:
//   replay SESSION --out DIR   run a recorded planning session headlessly
//   report SESSION --out DIR   replay it and write its plan report (HTML and PDF)
//   info MESH                  load a mesh file and print its topology summary
//   distance A B               Hausdorff distance between two mesh files
//   generate arch --out DIR    write the synthetic infant aortic arch and its landmarks
//   prepare MESH --out DIR     turn a segmentation export into a vessel to plan on
//   gui [SESSION]              the interactive planning window (records a session)
// Exit codes: 0 success, 1 the session or mesh failed (message on stderr), other non-zero
// codes for command-line usage errors (from CLI11).
#include <chrono>
#include <iostream>

#include <CLI/CLI.hpp>

#include "generate_command.hpp"
#include "gui_command.hpp"
#include "prepare_command.hpp"
#include "sutura/app/blas_restart.hpp"
#include "sutura/app/design_candidates.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/report.hpp"
#include "sutura/app/session_runner.hpp"
#include "sutura/engine/errors.hpp"
#include "sutura/engine/mesh_io.hpp"

namespace {

// `options` holds the output directory, threads and limits; progress is added here. With
// `plan_report`, a plan_report op (plan_report.html and .pdf) runs after the session's last
// line (as line 0: it is not in the file). Returns 0, or 2 when the time limit stopped the run
// (report.json has status "stopped").
int run_replay(const std::string& session_file, sutura::app::ReplayOptions options, bool quiet,
               bool plan_report) {
  using namespace sutura::app;
  const std::string out_dir = options.out_dir.string();
  Session session;
  try {
    session = load_session(session_file);
  } catch (const SessionError& error) {
    // report.json is written for every outcome, a session that does not parse included.
    try {
      SessionRunner runner(session_file, "", options);
      runner.write_report(runner.report("failed", error.what()));
    } catch (const std::exception&) {
      // The parse error matters more than a report that could not be written.
    }
    throw;
  }
  if (plan_report) {
    Action a;
    a.name = "plan_report";
    PlanReportOp op;
    op.file = "plan_report.html";
    op.pdf = "plan_report.pdf";
    a.op = op;
    a.source = {{"op", "plan_report"}, {"file", "plan_report.html"}, {"note", "added by sutura report"}};
    session.actions.push_back(std::move(a));
  }
  options.progress = quiet ? nullptr : &std::cerr;
  // Long runs (a relaxation can take minutes) show where they stand, at most once a second
  // so a run of thousands of dynamics steps does not flood the terminal.
  auto last_print = std::chrono::steady_clock::now();
  if (!quiet)
    options.on_progress = [&last_print](const RunProgress& p) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_print < std::chrono::seconds(1) && p.step < p.steps) return true;
      last_print = now;
      std::cerr << "\n    " << p.phase << " " << p.step << "/" << p.steps;
      if (p.s >= 0.0) std::cerr << ", s = " << p.s;
      if (p.residual >= 0.0) std::cerr << ", residual " << p.residual << " N";
      if (p.newton_iterations >= 0) std::cerr << ", " << p.newton_iterations << " Newton iterations";
      if (p.quasi_newton_iterations > 0)
        std::cerr << (p.newton_iterations >= 0 ? " + " : ", ") << p.quasi_newton_iterations
                  << " quasi-Newton steps";
      std::cerr << std::flush;
      return true;
    };
  if (!quiet)
    std::cerr << "sutura: replaying " << session_file << " (" << session.actions.size()
              << " actions) into " << out_dir << "/\n";
  const ReplayResult result = replay(session, options);
  if (result.stopped) {
    std::cerr << "sutura: stopped: " << result.report["error"].get<std::string>() << "; report: " << out_dir
              << "/report.json\n";
    return 2;
  }
  if (!quiet) {
    for (const auto& o : result.workspace.objects())
      std::cerr << "sutura: object '" << o.name << "': " << o.mesh.num_vertices()
                << " vertices, " << o.mesh.num_faces() << " faces, position hash "
                << position_hash(o.mesh) << "\n";
    std::cerr << "sutura: done in " << result.report["total_seconds"].get<double>()
              << " s; report: " << out_dir << "/report.json\n";
  }
  if (plan_report)
    std::cout << out_dir << "/plan_report.html\n" << out_dir << "/plan_report.pdf\n";
  return 0;
}

int run_info(const std::string& mesh_file, double weld_tolerance) {
  using namespace sutura;
  engine::ImportOptions io;
  io.weld_tolerance = weld_tolerance;
  app::SceneObject obj;
  obj.name = mesh_file;
  obj.mesh = engine::load_mesh(mesh_file, io);
  const auto report = obj.mesh.validate();
  nlohmann::json j = app::object_summary(obj);
  j["file"] = mesh_file;
  j["valid"] = report.ok();
  if (!report.ok()) j["problems"] = report.problems;
  std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";  // file names are any bytes
  return report.ok() ? 0 : 1;
}

// Hausdorff distance between two mesh files, as JSON on stdout.
int run_distance(const std::string& a_file, const std::string& b_file, double spacing) {
  using namespace sutura;
  const engine::SurfaceMesh a = engine::load_mesh(a_file), b = engine::load_mesh(b_file);
  nlohmann::json j = app::hausdorff_json(engine::hausdorff_distance(a, b, spacing));
  j["a"] = a_file;
  j["b"] = b_file;
  std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";  // file names are any bytes
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sutura::app::restart_with_better_blas_kernels(argv);  // first: OpenBLAS's kernels (blas_restart.hpp)
  CLI::App app{"Sutura: thin-shell surgical planning for congenital heart defect repair"};
  app.set_version_flag("--version", std::string("sutura ") + SUTURA_VERSION);
  app.require_subcommand(1);

  std::string session_file, out_dir = "out";
  bool quiet = false;
  int threads = 0;
  sutura::app::ReplayOptions replay_options;
  // The options of the two subcommands that run a session: replay and report.
  const auto add_run_options = [&](CLI::App* sub) {
    sub->add_option("session", session_file, "Session file (.jsonl)")->required();
    sub->add_option("-o,--out", out_dir, "Output directory (created if missing)")->capture_default_str();
    sub->add_flag("-q,--quiet", quiet, "No progress on stderr");
    sub->add_option("--threads", threads,
                    "Compute threads (OpenMP and BLAS); default: one per core. 1 is faster where "
                    "other processes keep the cores busy; positions then differ in the last bits")
        ->check(CLI::Range(1, 1024));
    sutura::app::Limits& limits = replay_options.limits;
    sub->add_option("--time-limit", replay_options.time_limit,
                    "Stop cleanly after this many seconds (report.json status \"stopped\", exit code 2); "
                    "default: none")
        ->check(CLI::PositiveNumber);
    sub->add_option("--max-faces", limits.faces_per_object, "Most faces of one object")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(1), std::size_t(20'000'000)));
    sub->add_option("--max-faces-in-all", limits.faces_in_all, "Most faces of all objects together")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(1), std::size_t(100'000'000)));
    sub->add_option("--max-objects", limits.objects, "Most objects")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(1), std::size_t(100'000)));
    sub->add_option("--max-steps", limits.steps,
                    "Most steps of one simulate (dynamics steps, relaxation increments and settling steps)")
        ->capture_default_str()
        ->check(CLI::Range(1L, 10'000'000L));
    sub->add_option("--max-pixels", limits.pixels, "Most pixels of one snapshot (all its views)")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(256), std::size_t(1) << 31));
    sub->add_option("--max-undo-mb", limits.undo_megabytes, "Most memory the undo history holds, MiB")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(0), std::size_t(1) << 20));
  };
  auto* replay = app.add_subcommand("replay", "Run a planning session headlessly; write snapshots, "
                                              "meshes and report.json into the output directory");
  add_run_options(replay);
  std::string emit_candidates;
  int candidate_count = 8;
  replay->add_option("--emit-candidates", emit_candidates,
                     "Run nothing: write each design_patch op's candidates into this directory as "
                     "sessions of their own, for a cluster's job array (docs/patch-design.md)");
  replay->add_option("--candidates", candidate_count,
                     "With --emit-candidates: widths per design_patch op, evenly spaced over its range")
      ->capture_default_str()
      ->check(CLI::Range(2, 1000));
  auto* report = app.add_subcommand(
      "report", "Replay a planning session and write its plan report, plan_report.html and "
                "plan_report.pdf, with the replay's outputs into the output directory");
  add_run_options(report);

  std::string mesh_file;
  double weld = 1e-6;
  auto* info = app.add_subcommand("info", "Load a mesh file (STL, OBJ, PLY) and print a summary");
  info->add_option("mesh", mesh_file, "Mesh file")->required();
  info->add_option("--weld-tolerance", weld,
                   "Weld vertices closer than this fraction of the bounding-box diagonal")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 0.01));

  std::string distance_a, distance_b;
  double spacing = 0.0;
  auto* distance = app.add_subcommand(
      "distance", "Hausdorff distance between two mesh files (one-sided both ways, symmetric)");
  distance->add_option("a", distance_a, "Mesh file A")->required();
  distance->add_option("b", distance_b, "Mesh file B")->required();
  distance->add_option("--spacing", spacing,
                       "mm between samples on each surface (default: half the smaller mean edge)")
      ->check(CLI::PositiveNumber);

  sutura::app::GenerateArchOptions arch_options;
  auto* arch = sutura::app::add_generate_command(app, arch_options);
  sutura::app::PrepareOptions prepare_options;
  auto* prepare = sutura::app::add_prepare_command(app, prepare_options);
  sutura::ui::GuiOptions gui_options;
  auto* gui = sutura::app::add_gui_command(app, gui_options);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*replay && !emit_candidates.empty()) {
      const auto written = sutura::app::emit_design_candidates(sutura::app::load_session(session_file),
                                                               emit_candidates, candidate_count);
      std::cout.precision(17);
      for (const auto& c : written) std::cout << c.file.string() << "\t" << c.width << "\n";
      return 0;
    }
    if (*replay || *report) {
      replay_options.out_dir = out_dir;
      replay_options.threads = threads;
      return run_replay(session_file, replay_options, quiet, static_cast<bool>(*report));
    }
    if (*info) return run_info(mesh_file, weld);
    if (*distance) return run_distance(distance_a, distance_b, spacing);
    if (*arch) return sutura::app::run_generate_arch(arch_options);
    if (*prepare) return sutura::app::run_prepare(prepare_options);
    if (*gui) return sutura::ui::run_gui(gui_options);
  } catch (const std::exception& e) {
    std::cerr << "sutura: error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
