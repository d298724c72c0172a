// plan_report: the plan report as one HTML file (parsed here as XML) and a PDF of it
// (rasterised by poppler), with every section.
#include "sutura/app/plan_report.hpp"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../render/pdf_structure.hpp"
#include "replay_fixture.hpp"
#include "sutura/render/image.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sutura::app;
using nlohmann::json;

const std::string kHeader =
    "{\"format\": \"sutura-session\", \"version\": 3, \"description\": \"A patched tube & its report\"}\n";
// A tube held at both ends, inflated, incised along its side with a patch sewn in, relaxed
// under the pressure, its lumen measured along its axis.
const std::string kPatchedTube =
    "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30, "
    "\"segments_around\": 24, \"segments_along\": 30}\n"
    "{\"op\": \"material\", \"object\": \"t\", \"youngs_modulus\": 1.0, \"poisson_ratio\": 0.45, "
    "\"thickness\": 0.6, \"note\": \"infant wall <test>\"}\n"
    "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
    "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 10], [3.2, 2.4, 15], [4, 0, 20]]}\n"
    "{\"op\": \"patch\", \"object\": \"t\", \"start\": [4, 0, 10], \"end\": [4, 0, 20], \"width\": 4, "
    "\"material\": {\"youngs_modulus\": 3.0, \"poisson_ratio\": 0.45, \"thickness\": 0.4}, \"note\": \"pericardium\"}\n"
    "{\"op\": \"pressure\", \"object\": \"t\", \"pressure\": 0.0107}\n"
    "{\"op\": \"simulate\", \"objects\": [\"t\"], \"relax\": {\"steps\": 3}}\n"
    "{\"op\": \"measure\", \"object\": \"t\", \"name\": \"lumen\", \"centreline\": [[0, 0, 2], [0, 0, 28]], "
    "\"stations\": 14}\n"
    "{\"op\": \"check\", \"measurement\": \"lumen\", \"quantity\": \"after.min_area_mm2\", \"range\": [1, 1000]}\n";
const std::string kReport =
    "{\"op\": \"plan_report\", \"file\": \"plan.html\", \"view_width\": 300, \"view_height\": 240}\n";

const std::vector<std::string> kSections = {"reproduce",   "plan",   "views",    "lumen",    "measurements",
                                            "equilibrium", "design", "template", "materials"};

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Reported {
  ReplayResult result;
  fs::path session, out;
  std::string html, pdf;
};

// The session file `session` replayed into `out`.
Reported replayed_into(const fs::path& session, const fs::path& out) {
  Reported r;
  r.session = session;
  ReplayOptions o;
  o.out_dir = out;
  r.result = replay(load_session(r.session), o);
  r.out = o.out_dir;
  r.html = read(r.out / "plan.html");
  r.pdf = read(r.out / "plan.pdf");
  return r;
}

// The session written to a file (its hash is part of the report) and replayed.
Reported replayed(const std::string& name, const std::string& text) {
  const fs::path dir = sutura::testing::scratch_dir("plan_report", name);
  std::ofstream(dir / "s.jsonl", std::ios::binary) << text;
  return replayed_into(dir / "s.jsonl", dir / "out");
}

const Reported& patched() {
  static const Reported r = replayed("tube", kHeader + kPatchedTube + kReport);
  return r;
}

const json& op_result(const Reported& r, const std::string& op) {
  for (const json& a : r.result.report["actions"])
    if (a["op"] == op) return a;
  throw std::runtime_error("no action " + op);
}

// The document parsed as XML (the report is polyglot HTML): its elements by id, its <img>
// sources and its inline <svg> count. Any parse error fails the test.
struct Parsed {
  std::map<std::string, std::string> text_by_id;  ///< all text under the element with that id
  std::vector<std::string> images;
  int svgs = 0;
  std::string title;
};

void walk(xmlNode* node, Parsed& p, std::string* collect) {
  for (xmlNode* n = node; n != nullptr; n = n->next) {
    std::string* into = collect;
    if (n->type == XML_ELEMENT_NODE) {
      const std::string name = reinterpret_cast<const char*>(n->name);
      if (name == "img") {
        xmlChar* src = xmlGetProp(n, reinterpret_cast<const xmlChar*>("src"));
        if (src) p.images.emplace_back(reinterpret_cast<const char*>(src));
        xmlFree(src);
      }
      if (name == "svg") ++p.svgs;
      xmlChar* id = xmlGetProp(n, reinterpret_cast<const xmlChar*>("id"));
      if (id) into = &p.text_by_id[reinterpret_cast<const char*>(id)];
      xmlFree(id);
      if (name == "title" && p.title.empty()) {
        xmlChar* t = xmlNodeGetContent(n);
        p.title = reinterpret_cast<const char*>(t);
        xmlFree(t);
      }
    } else if (n->type == XML_TEXT_NODE && collect != nullptr && n->content != nullptr) {
      *collect += reinterpret_cast<const char*>(n->content);
      *collect += ' ';
    }
    walk(n->children, p, into);
  }
}

Parsed parse(const std::string& html) {
  xmlDoc* doc = xmlReadMemory(html.data(), static_cast<int>(html.size()), "plan.html", "UTF-8",
                              XML_PARSE_NONET | XML_PARSE_NOWARNING);
  if (doc == nullptr) throw std::runtime_error("the report is not well-formed");
  Parsed p;
  walk(xmlDocGetRootElement(doc), p, nullptr);
  xmlFreeDoc(doc);
  return p;
}

TEST(PlanReport, HtmlParsesWithEverySection) {
  const Reported& r = patched();
  ASSERT_EQ(r.html.rfind("<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\"", 0), 0u);
  const Parsed p = parse(r.html);
  for (const std::string& id : kSections) EXPECT_TRUE(p.text_by_id.count(id)) << "section " << id;
  EXPECT_EQ(p.title, "Sutura plan report: s.jsonl");
  EXPECT_EQ(op_result(r, "plan_report")["sections"], json(kSections));
  // Three standard views and one lumen profile, each a PNG that decodes and is not blank.
  ASSERT_EQ(p.images.size(), 4u);
  EXPECT_EQ(op_result(r, "plan_report")["pictures"], 4);
  for (const std::string& src : p.images) {
    ASSERT_EQ(src.rfind("data:image/png;base64,", 0), 0u);
    std::string digits = src.substr(22);
    // Decode base64 (test-side) and the PNG.
    std::vector<std::uint8_t> bytes;
    std::uint32_t v = 0;
    int bits = 0;
    const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (char c : digits) {
      if (c == '=') break;
      v = (v << 6) | static_cast<std::uint32_t>(alphabet.find(c));
      bits += 6;
      if (bits >= 8) {
        bits -= 8;
        bytes.push_back(static_cast<std::uint8_t>((v >> bits) & 0xFF));
      }
    }
    const sutura::render::Image im = sutura::render::decode_png(bytes);
    int dark = 0;
    for (std::size_t i = 0; i < im.rgba.size(); i += 4) dark += im.rgba[i] < 200 || im.rgba[i + 1] < 200;
    EXPECT_GT(dark, im.width * im.height / 100) << "a picture is blank";
  }
  EXPECT_EQ(p.svgs, 1) << "the patch's template, inline";
  // Markup in the notes and the description is text, not markup.
  EXPECT_NE(r.html.find("infant wall &lt;test&gt;"), std::string::npos);
  EXPECT_NE(r.html.find("A patched tube &amp; its report"), std::string::npos);
}

TEST(PlanReport, SectionsSayWhatThePlanDid) {
  const Reported& r = patched();
  const Parsed p = parse(r.html);
  // Reproduce: the session's SHA-256 and size, and this program.
  const auto [sha, bytes] = file_sha256(r.session);
  EXPECT_NE(p.text_by_id.at("reproduce").find(sha), std::string::npos);
  EXPECT_NE(p.text_by_id.at("reproduce").find(std::to_string(bytes) + " bytes"), std::string::npos);
  EXPECT_NE(p.text_by_id.at("reproduce").find(program_version()), std::string::npos);
  // The plan: each step in words, with its note.
  const std::string& plan = p.text_by_id.at("plan");
  for (const char* step : {"Incise 't'", "pericardium", "infant wall <test>"})
    EXPECT_NE(plan.find(step), std::string::npos) << step << " in " << plan;
  // Measurements: before, after and change of the smallest area, as report.json has them.
  const json& m = r.result.report["measurements"]["lumen"];
  char before[32], after[32], change[32];
  std::snprintf(before, sizeof before, "%.2f", m["before"]["min_area_mm2"].get<double>());
  std::snprintf(after, sizeof after, "%.2f", m["after"]["min_area_mm2"].get<double>());
  std::snprintf(change, sizeof change, "%+.1f %%", m["min_area_change_percent"].get<double>());
  const std::string& table = p.text_by_id.at("measurements");
  const std::regex row(std::string("smallest lumen area \\(mm2\\) +") + before + " +" + after + " +" +
                       std::regex_replace(change, std::regex("[+]"), "\\+"));
  EXPECT_TRUE(std::regex_search(table, row)) << table;
  // The tube is inflated only after the incision: "before" is unloaded, and the report says so.
  EXPECT_NE(table.find("'t': before is the vessel unloaded"), std::string::npos) << table;
  EXPECT_NE(table.find("pass"), std::string::npos) << "the check";
  // Equilibrium of the relaxation; materials with the lines that set them.
  EXPECT_NE(p.text_by_id.at("equilibrium").find("relaxed to s = 1"), std::string::npos) << p.text_by_id.at("equilibrium");
  const std::string& materials = p.text_by_id.at("materials");
  EXPECT_NE(materials.find("line 3: "), std::string::npos) << materials;
  EXPECT_NE(materials.find("line 6: "), std::string::npos) << materials;
  EXPECT_NE(materials.find("(pericardium)"), std::string::npos) << materials;
  EXPECT_NE(p.text_by_id.at("design").find("No patch was designed"), std::string::npos);
}

// The PDF: its pages rasterised by poppler, none blank; the report's pages come first, the
// template's page (A4 at 1:1) last; the section headings are in its content streams.
TEST(PlanReport, PdfRasterisesWithEveryPage) {
  const Reported& r = patched();
  const int pages = op_result(r, "plan_report")["pdf_pages"].get<int>();
  ASSERT_GE(pages, 3);
  for (const char* heading : {"(Session and program) Tj", "(Plan steps) Tj", "(Before and after) Tj",
                              "(Lumen profile) Tj", "(Measurements) Tj", "(Equilibrium) Tj", "(Patch design) Tj",
                              "(Patch templates) Tj", "(Materials) Tj", "(PROXIMAL) Tj"})
    EXPECT_NE(r.pdf.find(heading), std::string::npos) << heading;
  const std::string prefix = (r.out / "page").string();
  const std::string command = "pdftoppm -r 30 -gray " + (r.out / "plan.pdf").string() + " " + prefix;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  for (int i = 1; i <= pages; ++i) {
    char name[64];
    std::snprintf(name, sizeof name, "-%0*d.pgm", pages >= 10 ? 2 : 1, i);
    const std::string pgm = read(prefix + name);
    ASSERT_FALSE(pgm.empty()) << "page " << i << " was not rasterised";
    std::istringstream in(pgm);
    std::string magic;
    int w = 0, h = 0, max = 0;
    in >> magic >> w >> h >> max;
    ASSERT_EQ(magic, "P5");
    EXPECT_NEAR(w, 248, 1) << "A4 at 30 dpi";
    const std::size_t data = pgm.size() - static_cast<std::size_t>(w * h);
    int dark = 0;
    for (std::size_t k = data; k < pgm.size(); ++k) dark += static_cast<unsigned char>(pgm[k]) < 200;
    EXPECT_GT(dark, 100) << "page " << i << " is blank";
  }
}

// The report's PDF: every object where the cross-reference table says, every stream as long
// as its /Length (poppler repairs a broken table, so rasterising alone would not tell).
TEST(PlanReport, PdfCrossReferencesHold) { EXPECT_TRUE(sutura::testing::pdf_structure_holds(patched().pdf)); }

TEST(PlanReport, IsDeterministic) {
  const Reported again = replayed_into(patched().session, patched().out.parent_path() / "again");
  EXPECT_EQ(again.pdf, patched().pdf);
  EXPECT_EQ(again.html, patched().html);
}

// A plan without patch, measurement or simulation: the sections say so.
TEST(PlanReport, EmptySectionsSaySo) {
  const Reported r = replayed(
      "bare", std::string("{\"format\": \"sutura-session\", \"version\": 3}\n") +
                  "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
                  "\"segments_around\": 16, \"segments_along\": 10}\n" +
                  kReport);
  const Parsed p = parse(r.html);
  EXPECT_NE(p.text_by_id.at("lumen").find("No lumen profile was measured"), std::string::npos);
  EXPECT_NE(p.text_by_id.at("measurements").find("No measurement was taken"), std::string::npos);
  EXPECT_NE(p.text_by_id.at("equilibrium").find("not equilibria"), std::string::npos);
  EXPECT_NE(p.text_by_id.at("template").find("No patch is sewn in"), std::string::npos);
  EXPECT_NE(p.text_by_id.at("materials").find("default values"), std::string::npos);
  EXPECT_NE(p.text_by_id.at("views").find("'t': before is the vessel as it was loaded or generated; nothing loads it"),
            std::string::npos);
  EXPECT_EQ(p.images.size(), 3u);
}

TEST(PlanReport, BadFieldsAreNamed) {
  const std::string base = kHeader +
                           "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, "
                           "\"length\": 20, \"segments_around\": 16, \"segments_along\": 10}\n";
  const auto error = [&](const std::string& line) {
    try {
      (void)parse_session(base + line, "s.jsonl");
    } catch (const SessionError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("{\"op\": \"plan_report\", \"file\": \"plan.pdf\"}").find("field 'file'"), std::string::npos);
  EXPECT_NE(error("{\"op\": \"plan_report\", \"file\": \"../plan.html\"}").find("field 'file'"), std::string::npos);
  EXPECT_NE(error("{\"op\": \"plan_report\", \"file\": \"p.html\", \"pdf\": \"p.svg\"}").find("field 'pdf'"),
            std::string::npos);
  EXPECT_NE(error("{\"op\": \"plan_report\", \"file\": \"p.html\", \"view_width\": 10}").find("field 'view_width'"),
            std::string::npos);
  EXPECT_NE(error("{\"op\": \"plan_report\", \"file\": \"p.html\", \"colour\": 1}").find("field 'colour'"),
            std::string::npos);
  // The views count against --max-pixels, before the session runs.
  ReplayOptions o;
  o.out_dir = sutura::testing::scratch_dir("plan_report", "pixels");
  o.limits.pixels = 100000;
  try {
    (void)replay(parse_session(base + "{\"op\": \"plan_report\", \"file\": \"p.html\"}\n", "s.jsonl"), o);
    ADD_FAILURE() << "no error";
  } catch (const SessionError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-pixels"), std::string::npos) << e.what();
  }
}

// Notes and names are any text: the HTML stays well-formed XML (invalid UTF-8, control bytes
// and non-characters become U+FFFD, markup is escaped), a note of 20,000 characters without a
// space is laid out in time, cut in the PDF's table and whole in the HTML.
TEST(PlanReport, AnyTextStaysWellFormed) {
  const std::string long_word(20000, 'x');
  const std::string odd = "caf\xC3\xA9 \xFF\xFE bad \xED\xA0\x80 surrogate \xEF\xBF\xBF nonchar \x01 ctl \xE2\x80\x94 dash";
  json note_line = {{"op", "material"}, {"object", "t"}, {"youngs_modulus", 1.0}, {"note", odd}};
  json long_line = {{"op", "fix"}, {"object", "t"}, {"boundary", "all"}, {"note", long_word}};
  // A file name is any bytes: this one is not UTF-8.
  const fs::path dir = sutura::testing::scratch_dir("plan_report", "odd");
  const fs::path session = dir / "plan \xFF\xC3.jsonl";
  std::ofstream(session, std::ios::binary)
      << "{\"format\": \"sutura-session\", \"version\": 3}\n"
         "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 20, "
         "\"segments_around\": 16, \"segments_along\": 10}\n"
      << note_line.dump(-1, ' ', false, json::error_handler_t::ignore) << "\n"
      << long_line.dump() << "\n"
      << kReport;
  const Reported r = replayed_into(session, dir / "out");
  const Parsed p = parse(r.html);  // throws when not well-formed
  EXPECT_EQ(p.title, "Sutura plan report: plan \xEF\xBF\xBD\xEF\xBF\xBD.jsonl");
  const std::string& plan = p.text_by_id.at("plan");
  EXPECT_NE(plan.find("caf\xC3\xA9"), std::string::npos) << "valid UTF-8 is kept";
  EXPECT_NE(plan.find("\xE2\x80\x94 dash"), std::string::npos);
  EXPECT_NE(plan.find(long_word), std::string::npos) << "the HTML has the whole note";
  EXPECT_NE(r.pdf.find("([cut here: the HTML has the whole text]) Tj"), std::string::npos) << "the PDF's row is at most a page";
  EXPECT_NE(r.pdf.find("- dash"), std::string::npos) << "the dash spelled out for Helvetica";
}

// SHA-256 of files against FIPS 180-4's examples.
TEST(PlanReport, Sha256OfFiles) {
  const fs::path dir = sutura::testing::scratch_dir("plan_report", "sha");
  std::ofstream(dir / "empty", std::ios::binary).flush();
  std::ofstream(dir / "abc", std::ios::binary) << "abc";
  EXPECT_EQ(file_sha256(dir / "empty"),
            std::make_pair(std::string("e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"),
                           std::uintmax_t{0}));
  EXPECT_EQ(file_sha256(dir / "abc"),
            std::make_pair(std::string("ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"),
                           std::uintmax_t{3}));
  EXPECT_THROW((void)file_sha256(dir / "missing"), std::runtime_error);
}

}  // namespace
