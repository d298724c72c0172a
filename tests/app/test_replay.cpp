#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <thread>
#include <utility>

#include "replay_fixture.hpp"
#include "sutura/app/object_view.hpp"
#include "sutura/app/replay.hpp"
#include "sutura/app/report.hpp"
#include "sutura/app/session_runner.hpp"
#include "sutura/engine/blas_kernels.hpp"
#include "sutura/engine/compute_threads.hpp"
#include "sutura/engine/generators.hpp"
#include "sutura/engine/measure/vertex_fields.hpp"
#include "sutura/engine/shell/shell_model.hpp"
#include "sutura/engine/mesh_io.hpp"
#include "sutura/render/image.hpp"

namespace fs = std::filesystem;
using namespace sutura::app;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("sutura_replay_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

sutura::render::Image read_png(const fs::path& p) {
  std::string bytes = read_text(p);
  return sutura::render::decode_png(std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
}

// The inflated aortic segment: a quick session exercising snapshots, fields and exports.
const fs::path kInflationSession = fs::path(SUTURA_ASSETS_DIR) / "sessions" / "inflation.jsonl";

// Runs the sutura executable (after `env`, e.g. "env VAR=value "); returns its exit status and
// captures stderr.
int run_sutura(const std::string& args, std::string* err_out, const std::string& env = "") {
  fs::path err = fs::temp_directory_path() / ("sutura_stderr_" + std::to_string(::getpid()));
  const std::string cmd = env + std::string(SUTURA_EXE) + " " + args + " 2> " + err.string();
  const int status = std::system(cmd.c_str());
  if (err_out) *err_out = read_text(err);
  fs::remove(err);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(Replay, DefaultSessionWritesSnapshotsMeshesAndReport) {
  fs::path out = fresh_dir("default");
  std::ostringstream progress;
  ReplayOptions options;
  options.out_dir = out;
  options.progress = &progress;
  ReplayResult result = replay(load_session(kInflationSession), options);

  EXPECT_NE(progress.str().find("snapshot"), std::string::npos);
  ASSERT_TRUE(fs::exists(out / "report.json"));
  auto report = nlohmann::json::parse(read_text(out / "report.json"));
  EXPECT_EQ(report["status"], "ok");
  EXPECT_EQ(report["actions"].size(), 13u);
  EXPECT_GT(report["probes"]["mid_wall"]["ux"].get<double>(), 0.1);  // inflated outwards
  for (const auto& a : report["actions"]) EXPECT_GE(a["seconds"].get<double>(), 0.0);
  EXPECT_EQ(report["objects"]["aorta"]["boundary_loop_sizes"].size(), 2u);
  EXPECT_EQ(report["objects"]["aorta"]["position_hash"],
            position_hash(result.workspace.find("aorta")->mesh));

  // Side-by-side before|after: twice as wide as one view (plus the gap), taller for captions.
  auto both = read_png(out / "before_after.png");
  EXPECT_GT(both.width, 2 * 960);
  EXPECT_GE(both.height, 720);
  auto single = read_png(out / "after.png");
  EXPECT_EQ(single.width, 1280);
  EXPECT_EQ(single.height, 960);
  // Background at the corners; the vessel across the middle row, left of the image's centre
  // when a legend's column takes the right edge (the scene is centred left of it).
  const auto bg = single.pixel(0, 0);
  EXPECT_EQ(single.pixel(single.width - 1, single.height - 1), bg);
  // The middle of the first run of vessel pixels along the middle row of `image`.
  const auto vessel_column = [](const auto& image) {
    const auto background = image.pixel(0, 0);
    int first = -1, last = -1;
    for (int x = 0; x < image.width; ++x) {
      const bool vessel = image.pixel(x, image.height / 2) != background;
      if (vessel && first < 0) first = x;
      if (!vessel && first >= 0) break;
      if (vessel) last = x;
    }
    return first < 0 ? -1 : (first + last) / 2;
  };
  const int middle = vessel_column(single);
  EXPECT_GT(middle, single.width / 4);
  EXPECT_LE(middle, single.width / 2 + single.width / 20);

  // Membrane strain map: the inflated wall is coloured, so the image is not one flat colour
  // apart from the background.
  auto strain = read_png(out / "strain.png");
  const int column = vessel_column(strain);
  ASSERT_GT(column, 0);
  std::set<std::array<std::uint8_t, 4>> colours;
  for (int y = strain.height / 4; y < 3 * strain.height / 4; y += 7) colours.insert(strain.pixel(column, y));
  EXPECT_GT(colours.size(), 3u);
  auto aorta = sutura::engine::load_mesh(out / "meshes" / "aorta.obj");
  EXPECT_EQ(aorta.num_faces(), 2u * 32 * 48);
  auto patch = sutura::engine::load_mesh(out / "meshes" / "patch.stl");
  EXPECT_EQ(patch.num_faces(), result.workspace.find("patch")->mesh.num_faces());
  fs::remove_all(out);
}

TEST(Replay, IsDeterministic) {
  fs::path a = fresh_dir("det_a"), b = fresh_dir("det_b");
  ReplayOptions oa, ob;
  oa.out_dir = a;
  ob.out_dir = b;
  const Session s = load_session(kInflationSession);
  ReplayResult ra = replay(s, oa), rb = replay(s, ob);
  for (const auto& obj : ra.workspace.objects())
    EXPECT_EQ(position_hash(obj.mesh), position_hash(rb.workspace.find(obj.name)->mesh));
  // Same pixels, byte for byte.
  EXPECT_EQ(read_text(a / "before_after.png"), read_text(b / "before_after.png"));
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(Replay, FailureNamesLineAndKeepsAReport) {
  fs::path dir = fresh_dir("fail");
  fs::path session = dir / "s.jsonl";
  std::ofstream(session) << "{\"format\": \"sutura-session\", \"version\": 1}\n"
                         << "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\"}\n"
                         << "{\"op\": \"export\", \"object\": \"missing\", \"file\": \"m.obj\"}\n";
  ReplayOptions o;
  o.out_dir = dir / "out";
  try {
    replay(load_session(session), o);
    FAIL() << "replay should fail";
  } catch (const SessionError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("no object named 'missing'"), std::string::npos);
  }
  auto report = nlohmann::json::parse(read_text(dir / "out" / "report.json"));
  EXPECT_EQ(report["status"], "failed");
  EXPECT_NE(report["error"].get<std::string>().find(":3:"), std::string::npos);
  EXPECT_TRUE(report["objects"].contains("a"));
  fs::remove_all(dir);
}

TEST(Replay, LoadsMeshRelativeToSessionAndReportsBadMeshWithFileName) {
  fs::path dir = fresh_dir("load");
  fs::create_directories(dir / "meshes");
  std::ofstream(dir / "meshes" / "bad.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
  std::ofstream(dir / "s.jsonl") << "{\"format\": \"sutura-session\", \"version\": 1}\n"
                                 << "{\"op\": \"load\", \"object\": \"a\", \"file\": \"meshes/bad.obj\"}\n";
  ReplayOptions o;
  o.out_dir = dir / "out";
  try {
    replay(load_session(dir / "s.jsonl"), o);
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("bad.obj"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

TEST(SuturaCli, ReplayDefaultSessionEndToEnd) {
  fs::path out = fresh_dir("cli");
  std::string err;
  ASSERT_EQ(run_sutura("replay " + kInflationSession.string() + " --out " + out.string(), &err), 0)
      << err;
  EXPECT_NE(err.find("position hash"), std::string::npos);
  EXPECT_TRUE(fs::exists(out / "before_after.png"));
  EXPECT_TRUE(fs::exists(out / "meshes" / "aorta.obj"));
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "report.json"))["status"], "ok");
  fs::remove_all(out);
}

// OpenBLAS 0.3.21 falls back to generic kernels on CPUs newer than itself; sutura restarts
// itself with the kernels the CPU supports (blas_kernels.hpp), unless the user chose them.
TEST(SuturaCli, RunsWithTheBlasKernelsTheCpuSupports) {
  const auto blas_of_replay = [](const std::string& env) {
    fs::path out = fresh_dir("blas");
    std::string err;
    EXPECT_EQ(run_sutura("replay " + kInflationSession.string() + " -q --out " + out.string(), &err,
                         env),
              0)
        << err;
    const auto report = nlohmann::json::parse(read_text(out / "report.json"));
    fs::remove_all(out);
    return report["blas"].get<std::string>();
  };
  // This test process loaded OpenBLAS without the restart, so it sees OpenBLAS's own choice.
  const char* better = sutura::engine::better_blas_coretype();
  const std::string expected = better != nullptr ? std::string("OpenBLAS ") + better
                                                 : sutura::engine::blas_kernels_in_use();
  EXPECT_EQ(blas_of_replay(""), expected);
  if (expected.rfind("OpenBLAS", 0) == 0) {
    EXPECT_EQ(blas_of_replay("env OPENBLAS_CORETYPE=Prescott "), "OpenBLAS Prescott");
  }
}

// --threads sets the compute threads (OpenMP and BLAS); the report records them, and the same
// count gives the same positions run after run. Since the factorisations and the
// single-precision solves of large systems run the same operations on one thread as on two
// (parallel_cholesky.hpp, single_precision_factor.hpp), the default session's positions do not
// depend on the count at all.
TEST(SuturaCli, ThreadsOptionSetsAndReportsTheThreadCount) {
  const auto replay_with = [](const std::string& option) {
    fs::path out = fresh_dir("threads");
    std::string err;
    EXPECT_EQ(run_sutura("replay " + kInflationSession.string() + " -q " + option + " --out " +
                             out.string(),
                         &err),
              0)
        << err;
    auto report = nlohmann::json::parse(read_text(out / "report.json"));
    fs::remove_all(out);
    return report;
  };
  const auto a = replay_with("--threads 1"), b = replay_with("--threads 1");
  EXPECT_EQ(a.at("threads").at("openmp"), 1);
  if (sutura::engine::blas_kernels_in_use().rfind("OpenBLAS", 0) == 0) {
    EXPECT_EQ(a.at("threads").at("blas"), 1);
  }
  EXPECT_EQ(a.at("objects"), b.at("objects"));  // position hashes included
  EXPECT_EQ(a.at("objects"), replay_with("--threads 2").at("objects"));
  EXPECT_GE(replay_with("").at("threads").at("openmp").get<int>(), 1);
  std::string err;
  EXPECT_NE(run_sutura("replay " + kInflationSession.string() + " --threads 0", &err), 0);
  EXPECT_NE(err.find("--threads"), std::string::npos) << err;
}

TEST(SuturaCli, BadSessionExitsNonZeroWithLineNumber) {
  fs::path dir = fresh_dir("clibad");
  std::ofstream(dir / "s.jsonl") << "{\"format\": \"sutura-session\", \"version\": 1}\n"
                                 << "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\", \"radius\": 0}\n";
  std::string err;
  EXPECT_EQ(run_sutura("replay " + (dir / "s.jsonl").string() + " --out " + (dir / "out").string(), &err), 1);
  EXPECT_NE(err.find("s.jsonl:2"), std::string::npos) << err;
  EXPECT_NE(err.find("radius"), std::string::npos) << err;
  EXPECT_NE(run_sutura("replay /nonexistent.jsonl", &err), 0);
  EXPECT_NE(err.find("no such file"), std::string::npos) << err;
  EXPECT_NE(run_sutura("frobnicate", &err), 0);
  fs::remove_all(dir);
}

TEST(SuturaCli, EscapingSessionIsRejectedBeforeWriting) {
  fs::path dir = fresh_dir("cliesc");
  std::ofstream(dir / "s.jsonl") << "{\"format\": \"sutura-session\", \"version\": 1}\n"
                                 << "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\"}\n"
                                 << "{\"op\": \"export\", \"object\": \"a\", \"file\": \"../../escaped.obj\"}\n";
  std::string err;
  EXPECT_EQ(run_sutura("replay " + (dir / "s.jsonl").string() + " --out " + (dir / "out").string(), &err), 1);
  EXPECT_NE(err.find("s.jsonl:3"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir / "escaped.obj"));
  EXPECT_FALSE(fs::exists(dir.parent_path() / "escaped.obj"));
  fs::remove_all(dir);
}

TEST(Replay, FailedSolveIsRolledBackAndReported) {
  fs::path dir = fresh_dir("diverge");
  std::ofstream(dir / "s.jsonl")
      << "{\"format\": \"sutura-session\", \"version\": 1}\n"
      << "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"strip\", \"segments_length\": 8, \"segments_width\": 2}\n"
      << "{\"op\": \"fix\", \"object\": \"a\", \"box\": {\"min\": [-1, -10, -1], \"max\": [0.1, 10, 1]}}\n"
      << "{\"op\": \"force\", \"object\": \"a\", \"nearest\": [[40, 0, 0]], \"force\": [0, 0, 1]}\n"
      << "{\"op\": \"solve\", \"max_iterations\": 2}\n";
  ReplayOptions o;
  o.out_dir = dir / "out";
  try {
    replay(load_session(dir / "s.jsonl"), o);
    FAIL() << "a large rotation of a cantilever does not converge in 2 Newton iterations";
  } catch (const SessionError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_NE(std::string(e.what()).find("rolled back"), std::string::npos) << e.what();
  }
  auto report = nlohmann::json::parse(read_text(dir / "out" / "report.json"));
  EXPECT_EQ(report["status"], "failed");
  // The state is the last good one: the unloaded strip.
  const auto strip = sutura::engine::make_strip({40.0, 10.0, 8, 2});
  EXPECT_EQ(report["objects"]["a"]["position_hash"], position_hash(strip));
  fs::remove_all(dir);
}

TEST(Replay, SimulationOpsProduceProbesAndChecks) {
  const fs::path session = fs::path(SUTURA_ASSETS_DIR) / "sessions" / "benchmarks" / "sze_cantilever.jsonl";
  fs::path out = fresh_dir("sze");
  ReplayOptions o;
  o.out_dir = out;
  ReplayResult r = replay(load_session(session), o);
  ASSERT_TRUE(r.report["probes"].contains("tip"));
  EXPECT_EQ(r.report["checks"].size(), 2u);
  for (const auto& c : r.report["checks"]) EXPECT_TRUE(c["pass"].get<bool>());
  bool found = false;
  for (const auto& a : r.report["actions"])
    if (a["op"] == "solve") {
      found = true;
      EXPECT_TRUE(a["converged"].get<bool>());
      EXPECT_GT(a["history"].size(), 4u);
    }
  EXPECT_TRUE(found);
  fs::remove_all(out);
}

// A check on an object reads its quantities as report.json lists them: the strip's right
// triangles have a smallest angle of 45 degrees.
TEST(Replay, ObjectChecksReadTheReportsQuantities) {
  fs::path dir = fresh_dir("object_check");
  const std::string head =
      "{\"format\": \"sutura-session\", \"version\": 3}\n"
      "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"strip\", \"length\": 4, "
      "\"width\": 4, \"segments_length\": 4, \"segments_width\": 4}\n";
  const auto run = [&](const std::string& check) {
    std::ofstream(dir / "s.jsonl") << head << check << "\n";
    ReplayOptions o;
    o.out_dir = dir / "out";
    return replay(load_session(dir / "s.jsonl"), o);
  };
  const ReplayResult ok = run(
      "{\"op\": \"check\", \"object\": \"a\", \"quantity\": \"quality.min_angle_deg\", "
      "\"range\": [44.9, 45.1]}");
  ASSERT_EQ(ok.report["checks"].size(), 1u);
  EXPECT_EQ(ok.report["checks"][0]["object"], "a");
  EXPECT_NEAR(ok.report["checks"][0]["value"].get<double>(), 45.0, 1e-9);
  EXPECT_TRUE(ok.report["checks"][0]["pass"].get<bool>());
  EXPECT_TRUE(run("{\"op\": \"check\", \"object\": \"a\", \"quantity\": \"faces\", "
                  "\"value\": 32, \"abs_tol\": 0.5}")
                  .report["checks"][0]["pass"]
                  .get<bool>());
  const auto failure = [&](const std::string& check) {
    try {
      run(check);
    } catch (const SessionError& e) {
      EXPECT_EQ(e.line(), 3);
      return std::string(e.what());
    }
    ADD_FAILURE() << "no error for " << check;
    return std::string();
  };
  // Each check line, and what its error must say.
  const std::pair<const char*, const char*> refused[] = {
      {"{\"op\": \"check\", \"object\": \"a\", \"quantity\": \"rest_quality.min_angle_deg\", "
       "\"range\": [50, 90]}",
       "check failed: object 'a' rest_quality.min_angle_deg = 45"},
      {"{\"op\": \"check\", \"object\": \"a\", \"quantity\": \"quality.nope\", \"range\": [0, 1]}",
       "object 'a' has no quantity 'quality.nope'"},
      {"{\"op\": \"check\", \"object\": \"b\", \"quantity\": \"faces\", \"range\": [0, 1]}",
       "no object named 'b'"},
      {"{\"op\": \"check\", \"object\": \"a\", \"probe\": \"p\", \"quantity\": \"ux\", "
       "\"value\": 0, \"abs_tol\": 1}",
       "give one of probe, measurement or object"},
  };
  for (const auto& [check, says] : refused)
    EXPECT_NE(failure(check).find(says), std::string::npos) << check;
  fs::remove_all(dir);
}

TEST(Replay, SolveReportsWhetherTheStateIsAStableEquilibrium) {
  // The Sze strip (EI = 100, L = 10) clamped at x = 0 and compressed along its axis by a dead
  // line load: below Euler's P_1 = pi^2 EI / (4 L^2) = 2.47 the straight state is stable,
  // above it has one unstable mode, which the solve reports and warns about (it stays
  // straight: nothing pushes it sideways, and a solve never changes the state for the test).
  const auto session = [](double P) {
    std::ostringstream s;
    s << "{\"format\": \"sutura-session\", \"version\": 1}\n"
      << "{\"op\": \"generate\", \"object\": \"s\", \"shape\": \"strip\", \"length\": 10, \"width\": 1, "
         "\"segments_length\": 32, \"segments_width\": 2}\n"
      << "{\"op\": \"material\", \"object\": \"s\", \"youngs_modulus\": 1.2e6, \"poisson_ratio\": 0, "
         "\"thickness\": 0.1}\n"
      << "{\"op\": \"constrain\", \"object\": \"s\", \"plane\": {\"point\": [0, 0, 0], \"normal\": [1, 0, 0]}, "
         "\"dofs\": [\"all\"]}\n"
      << "{\"op\": \"line_load\", \"object\": \"s\", \"plane\": {\"point\": [10, 0, 0], \"normal\": [1, 0, 0]}, "
         "\"force_per_length\": [" << -P << ", 0, 0]}\n"
      << "{\"op\": \"solve\", \"check_stability\": true}\n";
    return s.str();
  };
  for (const double P : {2.0, 3.0}) {
    fs::path dir = fresh_dir("euler");
    std::ofstream(dir / "s.jsonl") << session(P);
    std::ostringstream progress;
    ReplayOptions o;
    o.out_dir = dir / "out";
    o.progress = &progress;
    const ReplayResult r = replay(load_session(dir / "s.jsonl"), o);
    const nlohmann::json solve = r.report.at("actions").back();
    ASSERT_EQ(solve.at("op"), "solve");
    const nlohmann::json eq = solve.at("equilibrium");
    if (P < 2.47) {
      EXPECT_TRUE(eq.at("stable").get<bool>()) << eq.dump();
      EXPECT_FALSE(solve.contains("warning"));
    } else {
      EXPECT_FALSE(eq.at("stable").get<bool>());
      EXPECT_EQ(eq.at("negative_modes").get<int>(), 1);
      EXPECT_NE(solve.at("warning").get<std::string>().find("solved shape is not a stable equilibrium"),
                std::string::npos);
      EXPECT_NE(progress.str().find("warning: the solved shape"), std::string::npos) << progress.str();
    }
    fs::remove_all(dir);
  }
}

// A solve with "minimize" (energy minimisation: quasi-Newton steps from the tangent at the
// unloaded start) reaches the equilibrium Newton's load-driven solve reaches: a tube with held
// ends inflated until the wall moves out by about 5 % of its radius.
TEST(Replay, SolveByEnergyMinimisationReachesTheNewtonEquilibrium) {
  const auto session = [](const std::string& extra) {
    return "{\"format\": \"sutura-session\", \"version\": 1}\n"
           "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, "
           "\"length\": 16, \"segments_around\": 24, \"segments_along\": 16}\n"
           "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 1, \"poisson_ratio\": 0.45, "
           "\"thickness\": 0.8}\n"
           "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
           "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.01}\n"
           "{\"op\": \"solve\", \"check_stability\": true" + extra + "}\n"
           "{\"op\": \"probe\", \"object\": \"t\", \"name\": \"mid\", \"point\": [4, 0, 8]}\n";
  };
  nlohmann::json solves[2], probes[2];
  int k = 0;
  for (const std::string extra : {"", ", \"minimize\": true"}) {
    fs::path dir = fresh_dir("minimize");
    std::ofstream(dir / "s.jsonl") << session(extra);
    ReplayOptions o;
    o.out_dir = dir / "out";
    const ReplayResult r = replay(load_session(dir / "s.jsonl"), o);
    ASSERT_EQ(r.report.at("status"), "ok") << r.report.dump();
    solves[k] = r.report.at("actions").at(4);
    probes[k] = r.report.at("actions").at(5);
    ++k;
    fs::remove_all(dir);
  }
  ASSERT_EQ(solves[1].at("op"), "solve");
  EXPECT_FALSE(solves[0].contains("quasi_newton_iterations"));
  EXPECT_GT(solves[1].at("quasi_newton_iterations").get<int>(), 0);
  EXPECT_LT(solves[1].at("iterations").get<int>(), solves[0].at("iterations").get<int>());
  EXPECT_TRUE(solves[1].at("equilibrium").at("stable").get<bool>());
  const auto u = [](const nlohmann::json& probe) {
    const auto& v = probe.at("values");
    return std::array<double, 3>{v.at("ux").get<double>(), v.at("uy").get<double>(),
                                 v.at("uz").get<double>()};
  };
  const auto a = u(probes[0]), b = u(probes[1]);
  EXPECT_GT(a[0], 0.1);  // the wall moved out (membrane theory, free ends: p R^2 / (E t) = 0.2)
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], 1e-7) << "component " << i;
}

// "minimize" needs a potential energy: a pressure reaching a free rim has none there (the open
// end z = 16 of a tube held only at z = 0), so the solve is refused before it starts, naming
// the object and a vertex of that rim.
TEST(Replay, SolveByEnergyMinimisationRefusesAPressureUpToAFreeRim) {
  fs::path dir = fresh_dir("minimize_rim");
  std::ofstream(dir / "s.jsonl")
      << "{\"format\": \"sutura-session\", \"version\": 1}\n"
         "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, "
         "\"length\": 16, \"segments_around\": 24, \"segments_along\": 16}\n"
         "{\"op\": \"fix\", \"object\": \"t\", \"boundary_near\": [[4, 0, 0]]}\n"
         "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.01}\n"
         "{\"op\": \"solve\", \"minimize\": true}\n";
  ReplayOptions o;
  o.out_dir = dir / "out";
  try {
    replay(load_session(dir / "s.jsonl"), o);
    FAIL() << "the pressure on the free end has no potential";
  } catch (const SessionError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.line(), 5);
    EXPECT_NE(what.find("pressure on 't' ends at a rim that is free to move"), std::string::npos)
        << what;
    EXPECT_NE(what.find(", 16.000) and 23 more"), std::string::npos) << what;
    EXPECT_NE(what.find("hold the rim"), std::string::npos) << what;
  }
  auto report = nlohmann::json::parse(read_text(dir / "out" / "report.json"));
  EXPECT_EQ(report["status"], "failed");
  fs::remove_all(dir);
}

// ReplayOptions::threads is applied on the thread that runs each op: a thread started later
// (the GUI's worker) would otherwise run with the default count, OpenMP's being per thread.
TEST(Replay, TheThreadCountIsSetOnTheThreadThatRunsTheOp) {
  fs::path dir = fresh_dir("threads_runner");
  std::ofstream(dir / "s.jsonl")
      << "{\"format\": \"sutura-session\", \"version\": 1}\n"
         "{\"op\": \"generate\", \"object\": \"s\", \"shape\": \"strip\"}\n";
  const Session session = load_session(dir / "s.jsonl");
  ReplayOptions o;
  o.out_dir = dir / "out";
  o.threads = 1;
  SessionRunner runner(session.file, session.description, o);
  int seen = -1;
  std::thread worker([&] {
    runner.execute(session.actions.at(0));
    seen = sutura::engine::compute_threads().openmp;
  });
  worker.join();
  EXPECT_EQ(seen, 1);
  fs::remove_all(dir);
}

TEST(Replay, OutputsNeverOverwriteTheSessionOrALoadedMesh) {
  const fs::path out = fresh_dir("no_overwrite");
  sutura::engine::save_mesh(sutura::engine::make_tube({2.0, 6.0, 8, 3}), out / "tube.ply");
  const std::string mesh_before = read_text(out / "tube.ply");
  const auto write = [&](const fs::path& p, const std::string& body) {
    std::ofstream(p, std::ios::binary) << R"({"format": "sutura-session", "version": 3})" "\n" << body;
  };
  // An export onto the mesh the session loaded.
  write(out / "export.jsonl", R"({"op": "load", "object": "t", "file": "tube.ply"})" "\n"
                              R"({"op": "export", "object": "t", "file": "tube.ply"})" "\n");
  ReplayOptions options;
  options.out_dir = out;
  try {
    replay(load_session(out / "export.jsonl"), options);
    ADD_FAILURE() << "the export overwrote its input";
  } catch (const SessionError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("input"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_text(out / "tube.ply"), mesh_before);
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "report.json"))["status"], "failed");
  // A report op onto the session being replayed.
  write(out / "r.json", R"({"op": "generate", "object": "t", "shape": "tube"})" "\n"
                        R"({"op": "report", "file": "r.json"})" "\n");
  const std::string session_before = read_text(out / "r.json");
  EXPECT_THROW(replay(load_session(out / "r.json"), options), SessionError);
  EXPECT_EQ(read_text(out / "r.json"), session_before);
  // A session named report.json inside the output directory: the report is not written over it.
  fs::rename(out / "r.json", out / "report.json");
  write(out / "report.json", R"({"op": "generate", "object": "t", "shape": "tube"})" "\n");
  const std::string named_report = read_text(out / "report.json");
  EXPECT_ANY_THROW(replay(load_session(out / "report.json"), options));
  EXPECT_EQ(read_text(out / "report.json"), named_report);
}

TEST(Replay, AParseErrorStillWritesAFailedReport) {
  const fs::path out = fresh_dir("parse_error_report");
  const fs::path session = out / "bad.jsonl";
  std::ofstream(session, std::ios::binary) << R"({"format": "sutura-session", "version": 3})" "\n"
                                           << R"({"op": "generate", "object": "t", "shape": "tube", "radius": 1e999})" "\n";
  std::string err;
  EXPECT_EQ(run_sutura("replay " + session.string() + " --out " + (out / "o").string() + " -q", &err), 1);
  EXPECT_NE(err.find("bad.jsonl:2"), std::string::npos) << err;
  ASSERT_TRUE(fs::exists(out / "o" / "report.json"));
  const auto report = nlohmann::json::parse(read_text(out / "o" / "report.json"));
  EXPECT_EQ(report["status"], "failed");
  EXPECT_NE(report["error"].get<std::string>().find("out of range"), std::string::npos);
}

TEST(Replay, FileNamesThatAreNotUtf8AreReportedNotFatal) {
  // A file name is any bytes; JSON text must be UTF-8. The name is written with U+FFFD.
  const fs::path out = fresh_dir("not_utf8");
  const fs::path mesh = out / std::string("tube\xff.ply");
  sutura::engine::save_mesh(sutura::engine::make_tube({2.0, 6.0, 8, 3}), mesh);
  std::string err;
  EXPECT_EQ(run_sutura("info '" + mesh.string() + "' > " + (out / "info.json").string(), &err), 0) << err;
  const auto info = nlohmann::json::parse(read_text(out / "info.json"));
  EXPECT_NE(info["file"].get<std::string>().find("tube\xEF\xBF\xBD.ply"), std::string::npos);
  const fs::path session = out / std::string("s\xfe.jsonl");
  std::ofstream(session, std::ios::binary) << R"({"format": "sutura-session", "version": 3})" "\n"
                                           << R"({"op": "generate", "object": "t", "shape": "tube"})" "\n";
  EXPECT_EQ(run_sutura("replay '" + session.string() + "' --out " + (out / "o").string() + " -q", &err), 0) << err;
  EXPECT_EQ(nlohmann::json::parse(read_text(out / "o" / "report.json"))["status"], "ok");
}

// Colour fields are measured with the model whose run produced the shape: after a Model 2
// (discrete) solve, its strain energy, not Model 1's (which differs: ANDES and DKT against
// constant-strain triangles and hinges).
// Both sides of a before/after comparison show the held ends: in the before state at their
// pre-operative positions (here the inflated tube, solved with as_before), one per held
// vertex, although an incision has changed the current mesh since.
// The tube "s" (R 4 mm, 16 x 10 segments, E 1 MPa, nu 0.45, t 0.6 mm) and then `steps`,
// run op by op in `dir` by a SessionRunner, which is returned with its workspace.
std::unique_ptr<SessionRunner> run_on_tube(const fs::path& dir, const std::string& steps) {
  std::ofstream(dir / "s.jsonl")
      << "{\"format\": \"sutura-session\", \"version\": 3}\n"
         "{\"op\": \"generate\", \"object\": \"s\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
         "\"segments_around\": 16, \"segments_along\": 10}\n"
         "{\"op\": \"material\", \"object\": \"s\", \"youngs_modulus\": 1.0, \"poisson_ratio\": 0.45, "
         "\"thickness\": 0.6}\n" << steps;
  const Session session = load_session(dir / "s.jsonl");
  ReplayOptions o;
  o.out_dir = dir / "out";
  auto runner = std::make_unique<SessionRunner>(session.file, session.description, o);
  for (const Action& a : session.actions) runner->execute(a);
  return runner;
}

TEST(Replay, TheBeforeViewShowsTheHeldVerticesWhereTheyWereBeforeTheSurgery) {
  const fs::path dir = fresh_dir("before_held");
  const auto runner = run_on_tube(
      dir,
      "{\"op\": \"fix\", \"object\": \"s\", \"boundary\": \"all\"}\n"
      "{\"op\": \"pressure\", \"object\": \"s\", \"pressure\": 0.0107}\n"
      "{\"op\": \"solve\", \"as_before\": true}\n"
      "{\"op\": \"incise\", \"object\": \"s\", \"points\": [[4.1, 0.2, 6.2], [4.1, 0.3, 13.7]]}\n");
  const SceneObject& obj = *runner->workspace().find("s");
  ASSERT_NE(obj.mesh.num_vertices(), obj.before.num_vertices());  // the incision added vertices
  const ObjectView after = object_view(obj, obj.mesh, {}, ViewContent{});
  const ObjectView before = object_view(obj, obj.before, {}, ViewContent{});
  ASSERT_EQ(after.held.size(), 32u);  // both end rings
  ASSERT_EQ(before.held.size(), after.held.size());
  for (const auto& p : before.held) {
    const sutura::engine::Vec3 x(p[0], p[1], p[2]);
    double nearest = 1e300;
    for (std::size_t v = 0; v < obj.before.num_vertices(); ++v)
      nearest = std::min(nearest, (obj.before.position(sutura::engine::VertexId(v)) - x).norm());
    EXPECT_LT(nearest, 1e-5) << "a held vertex off the before state's vertices";
  }
  ViewContent bare;
  bare.marks = false;
  EXPECT_TRUE(object_view(obj, obj.before, {}, bare).held.empty());
  fs::remove_all(dir);
}

TEST(Replay, FieldsOfAModel2RunComeFromModel2) {
  const fs::path dir = fresh_dir("fields_model");
  const auto runner = run_on_tube(
      dir,
      "{\"op\": \"fix\", \"object\": \"s\", \"boundary\": \"all\", \"dofs\": [\"translations\"]}\n"
      "{\"op\": \"pressure\", \"object\": \"s\", \"pressure\": 0.0107}\n"
      "{\"op\": \"solve\", \"model\": \"discrete\", \"load_steps\": 2}\n");
  const SceneObject& obj = *runner->workspace().find("s");
  EXPECT_EQ(obj.sim.state_model, sutura::engine::make_discrete_shell()->name());
  const std::vector<float> shown = field_values(Field::EnergyDensity, obj, obj.mesh);
  const auto energy = [&](const sutura::engine::ShellModel& model) {
    const sutura::engine::ShellProblem problem{&obj.mesh.faces(), &obj.sim.rest, &obj.sim.materials,
                                               &obj.sim.face_material, obj.mesh.num_vertices()};
    return sutura::engine::face_to_vertex(obj.mesh, model.measures(problem, obj.sim.state).energy_density);
  };
  const std::vector<double> model2 = energy(*sutura::engine::make_discrete_shell());
  const std::vector<double> model1 = energy(*sutura::engine::make_corotational_shell());
  ASSERT_EQ(shown.size(), model2.size());
  double off2 = 0.0, off1 = 0.0, top = 0.0;
  for (std::size_t v = 0; v < shown.size(); ++v) {
    off2 = std::max(off2, std::abs(shown[v] - model2[v]));
    off1 = std::max(off1, std::abs(shown[v] - model1[v]));
    top = std::max(top, model2[v]);
  }
  ASSERT_GT(top, 0.0);  // the tube is inflated
  EXPECT_LE(off2, 1e-6 * top);   // Model 2's, to float precision
  EXPECT_GT(off1, 1e-2 * top);   // and not Model 1's
  fs::remove_all(dir);
}

TEST(Replay, AModelWithoutRotationsRefusesHeldRotations) {
  // Model 2 has no rotation DOFs: a held rotation (fix's default, or constrain with rx) would
  // silently make a clamped end a pinned one, so the run is refused, naming the object, and
  // the same plan with only the translations held runs.
  const std::string head =
      "{\"format\": \"sutura-session\", \"version\": 3}\n"
      "{\"op\": \"generate\", \"object\": \"s\", \"shape\": \"strip\", \"length\": 10, \"width\": 2, "
      "\"segments_length\": 10, \"segments_width\": 2}\n"
      "{\"op\": \"force\", \"object\": \"s\", \"nearest\": [[10, 0, 0]], \"force\": [0, 0, 1e-6]}\n";
  const std::string clamp = "{\"op\": \"fix\", \"object\": \"s\", \"box\": {\"min\": [-1, -2, -1], \"max\": [1.1, 2, 1]}";
  const std::string solve = "{\"op\": \"solve\", \"model\": \"discrete\", \"analysis\": \"linear\"}\n";
  for (const std::string& held : {clamp + "}\n", clamp + ", \"dofs\": [\"ux\", \"uy\", \"uz\", \"rx\"]}\n"}) {
    const fs::path dir = fresh_dir("no_rotations");
    try {
      sutura::testing::replay_text(head + held + solve, dir);
      FAIL() << "a held rotation was ignored: " << held;
    } catch (const SessionError& e) {
      EXPECT_EQ(e.line(), 5);
      const std::string what = e.what();
      EXPECT_NE(what.find("no rotational degrees of freedom"), std::string::npos) << what;
      EXPECT_NE(what.find("vertices of 's' are held in rotation"), std::string::npos) << what;
    }
    fs::remove_all(dir);
  }
  const fs::path dir = fresh_dir("no_rotations_ok");
  const auto r = sutura::testing::replay_text(head + clamp + ", \"dofs\": [\"translations\"]}\n" + solve, dir);
  EXPECT_EQ(r.report["status"], "ok");
  fs::remove_all(dir);
}
