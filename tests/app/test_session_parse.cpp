#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "sutura/app/session.hpp"

using namespace sutura::app;

namespace {

const std::string kHeader = R"({"format": "sutura-session", "version": 1})" "\n";

Session parse(const std::string& body) { return parse_session(kHeader + body, "/data/s.jsonl"); }

// Parses and returns the error; fails the test if parsing succeeds.
SessionError parse_error(const std::string& text) {
  try {
    parse_session(text, "s.jsonl");
  } catch (const SessionError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a SessionError for:\n" << text;
  return SessionError("", 0, "", "", "");
}

}  // namespace

TEST(SessionParse, HeaderOnlyIsAnEmptySession) {
  Session s = parse("");
  EXPECT_EQ(s.version, 1);
  EXPECT_TRUE(s.actions.empty());
}

TEST(SessionParse, AllOpsWithFieldsAndLineNumbers) {
  Session s = parse(
      "{\"op\": \"generate\", \"object\": \"aorta\", \"shape\": \"tube\", \"radius\": 4.5, "
      "\"segments_around\": 24, \"translate\": [1, 2, 3]}\n"
      "\n"
      "{\"op\": \"load\", \"object\": \"pa\", \"file\": \"../meshes/pa.stl\"}\n"
      "{\"op\": \"snapshot\", \"file\": \"shots/a.png\", \"width\": 320, \"height\": 200, "
      "\"field\": \"z\", \"range\": [0, 5], \"side_by_side\": true, "
      "\"camera\": {\"view\": [0, 1, 0], \"fov_deg\": 40}, "
      "\"clip\": {\"point\": [1, 2, 3], \"normal\": [0, 0, -2]}}\n"
      "{\"op\": \"export\", \"object\": \"aorta\", \"file\": \"aorta.ply\", \"note\": \"final\"}\n"
      "{\"op\": \"report\", \"file\": \"r.json\"}\n");
  ASSERT_EQ(s.actions.size(), 5u);
  EXPECT_EQ(s.actions[0].line, 2);
  EXPECT_EQ(s.actions[1].line, 4);  // blank line 3 skipped
  const auto& g = std::get<GenerateOp>(s.actions[0].op);
  const auto& tube = std::get<sutura::engine::TubeParams>(g.params);
  EXPECT_DOUBLE_EQ(tube.radius, 4.5);
  EXPECT_EQ(tube.segments_around, 24);
  EXPECT_EQ(tube.segments_along, sutura::engine::TubeParams{}.segments_along);
  EXPECT_DOUBLE_EQ(g.translate[2], 3.0);
  const auto& l = std::get<LoadOp>(s.actions[1].op);
  EXPECT_EQ(l.file, std::filesystem::path("/data/../meshes/pa.stl"));
  const auto& snap = std::get<SnapshotOp>(s.actions[2].op);
  EXPECT_EQ(snap.width, 320);
  EXPECT_EQ(snap.field, Field::Z);
  ASSERT_TRUE(snap.range.has_value());
  EXPECT_DOUBLE_EQ((*snap.range)[1], 5.0);
  EXPECT_TRUE(snap.side_by_side);
  EXPECT_DOUBLE_EQ(snap.camera.view[1], 1.0);
  EXPECT_DOUBLE_EQ(snap.camera.fov_deg, 40.0);
  ASSERT_TRUE(snap.clip.has_value());
  EXPECT_DOUBLE_EQ(snap.clip->point[1], 2.0);
  EXPECT_DOUBLE_EQ(snap.clip->normal[2], -1.0);  // normalised
  EXPECT_FALSE(std::get<SnapshotOp>(parse("{\"op\": \"snapshot\", \"file\": \"b.png\"}\n")
                                        .actions[0].op).clip.has_value());
  EXPECT_EQ(std::get<ExportOp>(s.actions[3].op).file, std::filesystem::path("aorta.ply"));
}

// The dynamics scheme defaults to linearized, and to Newton with a relaxation (which uses
// Newton only).
TEST(SessionParse, SimulateSchemeDefaultsToLinearizedAndToNewtonWithARelaxation) {
  using sutura::engine::DynamicsScheme;
  Session s = parse(
      "{\"op\": \"simulate\", \"steps\": 5}\n"
      "{\"op\": \"simulate\", \"steps\": 5, \"scheme\": \"newton\"}\n"
      "{\"op\": \"simulate\", \"relax\": {\"steps\": 3}}\n");
  ASSERT_EQ(s.actions.size(), 3u);
  EXPECT_EQ(std::get<SimulateOp>(s.actions[0].op).params.scheme, DynamicsScheme::Linearized);
  EXPECT_EQ(std::get<SimulateOp>(s.actions[1].op).params.scheme, DynamicsScheme::Newton);
  EXPECT_EQ(std::get<SimulateOp>(s.actions[2].op).params.scheme, DynamicsScheme::Newton);
}

TEST(SessionParse, PatchShapes) {
  Session s = parse(
      "{\"op\": \"generate\", \"object\": \"p\", \"shape\": \"diamond\", \"length\": 12, "
      "\"width\": 5, \"edge_length\": 0.5}\n");
  const auto& p = std::get<sutura::engine::PatchParams>(std::get<GenerateOp>(s.actions[0].op).params);
  EXPECT_EQ(p.shape, sutura::engine::PatchShape::Diamond);
  EXPECT_DOUBLE_EQ(p.target_edge_length, 0.5);
}

// A session text that must fail, and what the error must say.
struct BadCase {
  std::string text;
  int line;
  std::string field;
  std::string phrase;
};

class SessionParseErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(SessionParseErrors, CitesLineFieldAndProblem) {
  const BadCase& c = GetParam();
  SessionError e = parse_error(c.text);
  EXPECT_EQ(e.line(), c.line) << e.what();
  EXPECT_EQ(e.field(), c.field) << e.what();
  EXPECT_NE(std::string(e.what()).find(c.phrase), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("s.jsonl"), std::string::npos) << e.what();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SessionParseErrors,
    ::testing::Values(
        BadCase{"", 0, "", "no header"},
        BadCase{"{\"op\": \"generate\"}\n", 1, "format", "first line must be the header"},
        BadCase{"{\"format\": \"other\", \"version\": 1}\n", 1, "format", "sutura-session"},
        BadCase{"{\"format\": \"sutura-session\", \"version\": 99}\n", 1, "version", "newer"},
        BadCase{kHeader + "{\"op\": \"generate\", \n", 2, "", "not valid JSON"},
        BadCase{kHeader + "[1, 2]\n", 2, "", "JSON object"},
        BadCase{kHeader + "{\"object\": \"a\"}\n", 2, "op", "missing"},
        BadCase{kHeader + "{\"op\": \"explode\"}\n", 2, "op", "unknown op"},
        BadCase{kHeader + "{\"op\": \"generate\", \"shape\": \"tube\"}\n", 2, "object", "missing"},
        BadCase{kHeader + "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"cube\"}\n", 2,
                "shape", "not one of"},
        BadCase{kHeader + "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\", "
                          "\"radius\": -1}\n",
                2, "radius", "greater than 0"},
        BadCase{kHeader + "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\", "
                          "\"radius\": \"big\"}\n",
                2, "radius", "must be a number"},
        BadCase{kHeader + "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\", "
                          "\"segments_around\": 2.5}\n",
                2, "segments_around", "whole number"},
        BadCase{kHeader + "{\"op\": \"generate\", \"object\": \"a\", \"shape\": \"tube\", "
                          "\"radus\": 3}\n",
                2, "radus", "unknown field"},
        BadCase{kHeader + "{\"op\": \"generate\", \"object\": \"a b\", \"shape\": \"tube\"}\n", 2,
                "object", "letters, digits"},
        BadCase{kHeader + "\n{\"op\": \"snapshot\", \"file\": \"x.jpg\"}\n", 3, "file", ".png"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"width\": 0}\n", 2,
                "width", "between"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"camera\": "
                          "{\"eye\": [0, 0, 1]}}\n",
                2, "camera.target", "together"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"camera\": "
                          "{\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"zoom\": 2}}\n",
                2, "camera.zoom", "unknown field"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"range\": [0, 1]}\n", 2,
                "range", "colour field"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"clip\": "
                          "{\"point\": [0, 0, 0], \"normal\": [0, 0, 0]}}\n",
                2, "clip.normal", "zero vector"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"clip\": "
                          "{\"normal\": [0, 0, 1]}}\n",
                2, "clip.point", "missing"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"clip\": "
                          "{\"point\": [1e31, 0, 0], \"normal\": [0, 0, 1]}}\n",
                2, "clip.point", "1e30"},
        BadCase{kHeader + "{\"op\": \"snapshot\", \"file\": \"a.png\", \"field\": \"z\", "
                          "\"range\": [1, 0]}\n",
                2, "range", "min < max"},
        BadCase{kHeader + "{\"op\": \"export\", \"object\": \"a\", \"file\": \"/tmp/a.obj\"}\n", 2,
                "file", "absolute"},
        BadCase{kHeader + "{\"op\": \"export\", \"object\": \"a\", \"file\": \"../a.obj\"}\n", 2,
                "file", "'..'"},
        BadCase{kHeader + "{\"op\": \"report\", \"file\": \"x/../../r.json\"}\n", 2, "file",
                "'..'"},
        BadCase{kHeader + "{\"op\": \"load\", \"object\": \"a\", \"file\": \"a.stl\", "
                          "\"weld_tolerance\": 0.5}\n",
                2, "weld_tolerance", "between"},
        BadCase{kHeader + "{\"op\": \"constrain\", \"object\": \"a\", \"vertices\": [1], "
                          "\"boundary\": \"all\"}\n",
                2, "", "exactly one vertex selection"},
        BadCase{kHeader + "{\"op\": \"constrain\", \"object\": \"a\", \"boundary\": \"all\", "
                          "\"dofs\": [\"uw\"]}\n",
                2, "", "unknown degree of freedom"},
        BadCase{kHeader + "{\"op\": \"force\", \"object\": \"a\", \"vertices\": [-1], "
                          "\"force\": [0, 0, 1]}\n",
                2, "vertices", "whole numbers"},
        BadCase{kHeader + "{\"op\": \"material\", \"object\": \"a\", \"poisson_ratio\": 0.5}\n",
                2, "poisson_ratio", "[0, 0.5)"},
        BadCase{kHeader + "{\"op\": \"body_force\", \"object\": \"a\"}\n", 2, "per_area",
                "exactly one"},
        BadCase{kHeader + "{\"op\": \"solve\", \"load_factor\": 1.5}\n", 2, "load_factor",
                "(0, 1]"},
        BadCase{kHeader + "{\"op\": \"solve\", \"model\": \"membrane\"}\n", 2, "model",
                "not one of"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"dt\": 0}\n", 2, "dt", "greater than 0"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"max_step_cuts\": 11}\n", 2, "max_step_cuts",
                "between"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"corotated_damping\": 1}\n", 2,
                "corotated_damping", "true or false"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"scheme\": \"explicit\"}\n", 2, "scheme",
                "not one of"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"scheme\": \"linearized\", "
                          "\"relax\": {}}\n",
                2, "scheme", "uses newton"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"relax\": {\"settle\": false, "
                          "\"settle_steps\": 30}}\n",
                2, "relax.settle_steps", "no effect"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"relax\": {\"density\": 1e-6}}\n", 2,
                "relax.density", "only the dynamic relaxation"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"relax\": {\"solver\": \"dynamic\", "
                          "\"density\": 0}}\n",
                2, "relax.density", "greater than 0"},
        BadCase{kHeader + "{\"op\": \"solve\", \"analysis\": \"linear\", \"check_stability\": true}\n",
                2, "check_stability", "nonlinear"},
        BadCase{kHeader + "{\"op\": \"solve\", \"analysis\": \"linear\", \"minimize\": true}\n",
                2, "minimize", "nonlinear"},
        BadCase{kHeader + "{\"op\": \"measure\", \"object\": \"a\", \"name\": \"m\", \"centreline\": \"automatic\", "
                          "\"from\": [0, 0, 0], \"to\": [0, 0, 1]}\n",
                2, "centreline", "\"auto\" or an array"},
        BadCase{kHeader + "{\"op\": \"measure\", \"object\": \"a\", \"name\": \"m\", \"centreline\": \"auto\", \"from\": [0, 0, 0]}\n",
                2, "to", "missing"},
        BadCase{kHeader + "{\"op\": \"measure\", \"object\": \"a\", \"name\": \"m\", \"centreline\": \"auto\", "
                          "\"from\": [1, 2, 3], \"to\": [1, 2, 3]}\n",
                2, "to", "differ"},
        BadCase{kHeader + "{\"op\": \"measure\", \"object\": \"a\", \"name\": \"m\", \"centreline\": [[0, 0, 0], [0, 0, 1]], "
                          "\"from\": [0, 0, 0]}\n",
                2, "from", ""},
        BadCase{kHeader + "{\"op\": \"load\", \"object\": \"a\", \"file\": \"x.stl\", \"prepare\": {\"smoothing\": 200}}\n",
                2, "prepare.smoothing", "100"},
        BadCase{kHeader + "{\"op\": \"load\", \"object\": \"a\", \"file\": \"x.stl\", \"prepare\": {\"edge_length\": -1}}\n",
                2, "prepare.edge_length", "greater than 0"},
        BadCase{kHeader + "{\"op\": \"load\", \"object\": \"a\", \"file\": \"x.stl\", \"prepare\": {\"keep\": 1}}\n",
                2, "prepare.keep", ""},
        BadCase{kHeader + "{\"op\": \"solve\", \"quasi_newton_steps\": 10}\n", 2,
                "quasi_newton_steps", "only with"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"relax\": {\"max_escapes\": -1}}\n", 2,
                "relax.max_escapes", "between"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"relax\": {\"quasi_newton_steps\": -3}}\n", 2,
                "relax.quasi_newton_steps", "between"},
        BadCase{kHeader + "{\"op\": \"simulate\", \"relax\": {\"check_stability\": 1}}\n", 2,
                "relax.check_stability", "true or false"},
        BadCase{kHeader + "{\"op\": \"check\", \"probe\": \"p\", \"quantity\": \"uz\", "
                          "\"value\": 1}\n",
                2, "rel_tol", "rel_tol and/or abs_tol"}),
    [](const ::testing::TestParamInfo<BadCase>& info) {
      std::string name = "line" + std::to_string(info.param.line) + "_" + info.param.field;
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name + "_" + std::to_string(info.index);
    });

TEST(SessionLoad, MissingFileAndDirectory) {
  EXPECT_THROW(load_session("/nonexistent/session.jsonl"), SessionError);
  try {
    load_session(std::filesystem::temp_directory_path());
    FAIL();
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos);
  }
}

TEST(SessionLoad, BundledSessionsParse) {
  int count = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::string(SUTURA_ASSETS_DIR) + "/sessions")) {
    if (entry.path().extension() != ".jsonl") continue;
    EXPECT_NO_THROW(load_session(entry.path())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 1);
}

TEST(SessionLoad, DevicesAndFifosAreRefusedBeforeTheyAreOpened) {
  // /dev/zero never ends and a FIFO blocks its reader until a writer comes: both would hang.
  for (const std::string& path : {std::string("/dev/zero"), std::string("/dev/null")}) {
    try {
      load_session(path);
      ADD_FAILURE() << path;
    } catch (const SessionError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
  const auto fifo = std::filesystem::temp_directory_path() / ("sutura_fifo_" + std::to_string(::getpid()));
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(load_session(fifo), SessionError);
  std::filesystem::remove(fifo);
}

TEST(SessionLoad, AFileOverTheSizeLimitIsRefused) {
  const auto big = std::filesystem::temp_directory_path() / ("sutura_big_" + std::to_string(::getpid()) + ".jsonl");
  {
    std::ofstream out(big, std::ios::binary);
    out << kHeader;
    const std::string blank(1 << 20, ' ');
    for (std::size_t written = kHeader.size(); written <= kMaxSessionBytes; written += blank.size()) out << blank;
  }
  try {
    load_session(big);
    ADD_FAILURE() << "a session over the limit was read";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("size limit"), std::string::npos) << e.what();
  }
  std::filesystem::remove(big);
}

TEST(SessionParse, DuplicateKeysAndNumberOverflowNameTheLine) {
  // nlohmann keeps the last of two equal keys: {"op": "material", ..., "op": "export"} would
  // silently run an export.
  const SessionError dup = parse_error(kHeader + R"({"op": "generate", "object": "t", "shape": "tube", "object": "u"})" "\n");
  EXPECT_EQ(dup.line(), 2);
  EXPECT_EQ(dup.field(), "object");
  EXPECT_NE(std::string(dup.what()).find("twice"), std::string::npos);
  const SessionError nested = parse_error(kHeader + R"({"op": "snapshot", "file": "a.png", "camera": {"view": [1, 0, 0], "view": [0, 1, 0]}})" "\n");
  EXPECT_EQ(nested.line(), 2);
  EXPECT_EQ(nested.field(), "view");
  // The same key in two different objects is fine.
  EXPECT_NO_THROW(parse(R"({"op": "generate", "object": "t", "shape": "tube"})" "\n"
                        R"({"op": "generate", "object": "u", "shape": "tube"})" "\n"));
  const SessionError big = parse_error(kHeader + R"({"op": "generate", "object": "t", "shape": "tube", "radius": 1e999})" "\n");
  EXPECT_EQ(big.line(), 2);
  EXPECT_NE(std::string(big.what()).find("out of range"), std::string::npos) << big.what();
  EXPECT_NE(std::string(big.what()).find("s.jsonl:2"), std::string::npos) << big.what();
}
