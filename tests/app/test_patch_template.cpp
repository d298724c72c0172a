// export_patch_template: the cutting template of a sewn-in patch, at true scale, in SVG and PDF.
#include "sutura/app/patch_template.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "replay_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sutura::app;
using nlohmann::json;

const std::string kHeader = "{\"format\": \"sutura-session\", \"version\": 3}\n";
// A tube held at both ends with an elliptic patch in a slit along it, relaxed: the patch is
// bent onto the tube, its rest shape is still the flat cut.
const std::string kPatchedTube =
    "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30, "
    "\"segments_around\": 24, \"segments_along\": 30}\n"
    "{\"op\": \"fix\", \"object\": \"t\", \"boundary\": \"all\"}\n"
    "{\"op\": \"incise\", \"object\": \"t\", \"points\": [[4, 0, 10], [3.2, 2.4, 15], [4, 0, 20]]}\n"
    "{\"op\": \"patch\", \"object\": \"t\", \"start\": [4, 0, 10], \"end\": [4, 0, 20], \"width\": 4, "
    "\"material\": {\"youngs_modulus\": 3.0, \"poisson_ratio\": 0.45, \"thickness\": 0.4}}\n"
    "{\"op\": \"simulate\", \"objects\": [\"t\"], \"relax\": {\"steps\": 3}}\n";
const std::string kExport =
    "{\"op\": \"export_patch_template\", \"object\": \"t\", \"file\": \"cut.svg\", \"proximal\": [4, 0, 10]}\n"
    "{\"op\": \"export_patch_template\", \"object\": \"t\", \"file\": \"cut.pdf\", \"proximal\": [4, 0, 10], "
    "\"bite_spacing\": 1.5, \"seam_allowance\": 1}\n";

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Exported {
  ReplayResult result;
  fs::path out;
};

const Exported& exported() {
  static const Exported e = [] {
    const fs::path dir = sutura::testing::scratch_dir("template", "tube");
    return Exported{sutura::testing::replay_text(kHeader + kPatchedTube + kExport, dir), dir / "out"};
  }();
  return e;
}

// The polygons of an SVG, in document units (mm), in order.
std::vector<std::vector<std::array<double, 2>>> svg_polygons(const std::string& svg) {
  std::vector<std::vector<std::array<double, 2>>> out;
  const std::regex polygon("<polygon points=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polygon); it != std::sregex_iterator(); ++it) {
    std::vector<std::array<double, 2>> points;
    std::istringstream in((*it)[1].str());
    std::string pair;
    while (in >> pair) {
      const auto comma = pair.find(',');
      points.push_back({std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1))});
    }
    out.push_back(points);
  }
  return out;
}

double perimeter(const std::vector<std::array<double, 2>>& p) {
  double l = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    l += std::hypot(p[(i + 1) % p.size()][0] - p[i][0], p[(i + 1) % p.size()][1] - p[i][1]);
  return l;
}

// The template's seam is the patch's rest shape: its length and area to 1e-9, no gap (the
// rest shape is the flat cut, though the patch is now bent onto the tube).
TEST(PatchTemplate, TheSeamIsTheRestShapeOfThePatch) {
  const json& a = exported().result.report["actions"];
  const json svg = a[a.size() - 2];
  ASSERT_EQ(svg["op"], "export_patch_template");
  EXPECT_NEAR(svg["seam_length_mm"].get<double>(), svg["rest_seam_length_mm"].get<double>(),
              1e-9 * svg["rest_seam_length_mm"].get<double>());
  EXPECT_NEAR(svg["area_mm2"].get<double>(), svg["rest_area_mm2"].get<double>(),
              1e-9 * svg["rest_area_mm2"].get<double>());
  EXPECT_LT(svg["max_gap_mm"].get<double>(), 1e-9);
  // A 4 mm ellipse along the 11.2 mm incision (its two lips' mean length).
  EXPECT_NEAR(svg["width_mm"].get<double>(), 4.0, 0.1);
  EXPECT_GT(svg["length_mm"].get<double>(), 10.0);
  EXPECT_LT(svg["length_mm"].get<double>(), 11.5);
  // Cut 2 mm outside a convex seam: longer by 2 pi * 2.
  EXPECT_NEAR(svg["cut_length_mm"].get<double>(), svg["seam_length_mm"].get<double>() + 4 * M_PI, 0.05);
  EXPECT_EQ(svg["bites"].get<int>(), static_cast<int>(std::floor(svg["seam_length_mm"].get<double>())));
  const json pdf = a.back();
  EXPECT_EQ(pdf["bites"].get<int>(), static_cast<int>(std::floor(pdf["seam_length_mm"].get<double>() / 1.5)));
  EXPECT_NEAR(pdf["cut_length_mm"].get<double>(), pdf["seam_length_mm"].get<double>() + 2 * M_PI, 0.05);

  // The polygons drawn: the cut line, then the seam (to the 1e-4 mm of the file's numbers).
  const auto polygons = svg_polygons(read(exported().out / "cut.svg"));
  ASSERT_EQ(polygons.size(), 2u);
  EXPECT_NEAR(perimeter(polygons[1]), svg["seam_length_mm"].get<double>(), 1e-3);
  EXPECT_NEAR(perimeter(polygons[0]), svg["cut_length_mm"].get<double>(), 1e-3);
  // Proximal up: the seam starts at its vertex nearest the proximal point, at the top.
  double top = 1e9;
  for (const auto& p : polygons[1]) top = std::min(top, p[1]);
  EXPECT_NEAR(polygons[1][0][1], top, 0.3);
}

// One unit is a millimetre: the SVG's page in mm with a viewBox in the same numbers, and the
// scale bar 10 units long; the PDF's MediaBox in points, its bar drawn in mm through 72/25.4.
TEST(PatchTemplate, TheScaleBarIsTenMillimetres) {
  const std::string svg = read(exported().out / "cut.svg");
  EXPECT_NE(svg.find("width=\"210mm\" height=\"297mm\" viewBox=\"0 0 210 297\""), std::string::npos);
  EXPECT_NE(svg.find("<polyline points=\"15,277 25,277\""), std::string::npos);
  EXPECT_NE(svg.find(">PROXIMAL</text>"), std::string::npos);
  EXPECT_NE(svg.find(">DISTAL</text>"), std::string::npos);
  const std::string pdf = read(exported().out / "cut.pdf");
  EXPECT_NE(pdf.find("/MediaBox [0 0 595.2756 841.8898]"), std::string::npos);
  EXPECT_NE(pdf.find("2.834646 0 0 -2.834646 0 841.889764 cm"), std::string::npos);
  EXPECT_NE(pdf.find("15 277 m\n25 277 l\nS\n"), std::string::npos);
}

// Printed: rasterised by poppler at 254 dpi (10 pixels a millimetre), the scale bar's row of
// dark pixels is 10 mm plus its round caps (0.3 mm line) long.
TEST(PatchTemplate, ThePdfRasterisesToScale) {
  const fs::path out = exported().out;
  const std::string command = "pdftoppm -r 254 -gray -x 100 -y 2720 -W 400 -H 100 " +
                              (out / "cut.pdf").string() + " " + (out / "bar").string();
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::string pgm = read(out / "bar-1.pgm");
  std::istringstream in(pgm);
  std::string magic;
  int w = 0, h = 0, max = 0;
  in >> magic >> w >> h >> max;
  ASSERT_EQ(magic, "P5");
  ASSERT_EQ(w, 400);
  ASSERT_EQ(h, 100);
  const std::size_t data = pgm.size() - static_cast<std::size_t>(w * h);
  // The bar's row (y 277 mm = pixel 2770, 50 into the crop): the longest run of dark pixels.
  int longest = 0;
  for (int y = 45; y < 55; ++y) {
    int run = 0;
    for (int x = 0; x < w; ++x) {
      const bool dark = static_cast<unsigned char>(pgm[data + y * w + x]) < 128;
      run = dark ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_GE(longest, 100);
  EXPECT_LE(longest, 104);
}

TEST(PatchTemplate, IsDeterministic) {
  const fs::path dir = sutura::testing::scratch_dir("template", "again");
  (void)sutura::testing::replay_text(kHeader + kPatchedTube + kExport, dir);
  EXPECT_EQ(read(dir / "out" / "cut.svg"), read(exported().out / "cut.svg"));
  EXPECT_EQ(read(dir / "out" / "cut.pdf"), read(exported().out / "cut.pdf"));
}

std::string failure(const std::string& text, const std::string& name) {
  try {
    (void)sutura::testing::replay_text(text, sutura::testing::scratch_dir("template", name));
  } catch (const std::exception& e) {
    return e.what();
  }
  return "no error";
}

TEST(PatchTemplate, BadRequestsNameTheField) {
  const std::string tube =
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30}\n";
  auto op = [](const std::string& fields) {
    return "{\"op\": \"export_patch_template\", \"object\": \"t\", " + fields + "}\n";
  };
  std::string e = failure(kHeader + tube + op("\"file\": \"c.svg\", \"proximal\": [4, 0, 10]"), "none");
  EXPECT_NE(e.find("has no patch"), std::string::npos) << e;
  e = failure(kHeader + kPatchedTube + op("\"file\": \"c.svg\", \"proximal\": [4, 0, 10], \"patch\": 2"), "two");
  EXPECT_NE(e.find("has 1 patch; there is no patch 2"), std::string::npos) << e;
  e = failure(kHeader + tube + op("\"file\": \"c.png\", \"proximal\": [4, 0, 10]"), "ext");
  EXPECT_NE(e.find("file"), std::string::npos) << e;
  e = failure(kHeader + tube + op("\"file\": \"c.svg\""), "proximal");
  EXPECT_NE(e.find("proximal"), std::string::npos) << e;
  e = failure(kHeader + tube + op("\"file\": \"c.svg\", \"proximal\": [4, 0, 10], \"seam_allowance\": -1"), "allow");
  EXPECT_NE(e.find("seam_allowance"), std::string::npos) << e;
  e = failure(kHeader + tube + op("\"file\": \"c.svg\", \"proximal\": [4, 0, 10], \"bite_spacing\": 0"), "bite");
  EXPECT_NE(e.find("bite_spacing"), std::string::npos) << e;
  e = failure(kHeader + tube + op("\"file\": \"c.svg\", \"proximal\": [4, 0, 10], \"bite_spacing\": 25"), "bite2");
  EXPECT_NE(e.find("bite_spacing"), std::string::npos) << e;
  e = failure(kHeader + tube + op("\"file\": \"c.svg\", \"proximal\": [4, 0, 10], \"bite_spacing\": 1e-300"), "bite3");
  EXPECT_NE(e.find("bite_spacing"), std::string::npos) << e;
}

// A part added beside the object (not sewn in) is not a patch; an upper-case .PDF is a PDF.
TEST(PatchTemplate, OnlySewnInPartsArePatches) {
  const std::string strip =
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"strip\", \"append\": true, "
      "\"length\": 10, \"width\": 3}\n";
  const std::string tube =
      "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, \"length\": 30}\n";
  const std::string e = failure(kHeader + tube + strip +
                                    "{\"op\": \"export_patch_template\", \"object\": \"t\", \"file\": \"c.svg\", "
                                    "\"proximal\": [4, 0, 10]}\n",
                                "strip");
  EXPECT_NE(e.find("has no patch"), std::string::npos) << e;
  const fs::path dir = sutura::testing::scratch_dir("template", "strip_and_patch");
  const ReplayResult r = sutura::testing::replay_text(
      kHeader + kPatchedTube + strip +
          "{\"op\": \"export_patch_template\", \"object\": \"t\", \"file\": \"c.PDF\", \"proximal\": [4, 0, 10]}\n",
      dir);
  const json& a = r.report["actions"].back();
  EXPECT_NEAR(a["seam_length_mm"].get<double>(),
              exported().result.report["actions"][exported().result.report["actions"].size() - 2]["seam_length_mm"].get<double>(),
              1e-9);
  EXPECT_EQ(read(dir / "out" / "c.PDF").rfind("%PDF-1.4", 0), 0u);
}

}  // namespace
