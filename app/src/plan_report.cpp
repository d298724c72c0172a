#include "sutura/app/plan_report.hpp"

#include <nettle/sha2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sutura/app/patch_template.hpp"
#include "sutura/render/chart.hpp"
#include "sutura/render/vector_page.hpp"
#include "design_chart.hpp"
#include "number_text.hpp"
#include "sutura_build_id.hpp"

namespace sutura::app {

using nlohmann::json;

namespace {

using detail::fixed;
using detail::general;

// ---- The document: blocks that both writers lay out -------------------------------------
//
// The report is built once as a list of blocks; to_html and to_pages write the same list, so
// the HTML and the PDF cannot say different things.

struct Table {
  std::vector<std::string> header;  ///< all empty: a table without a header row
  std::vector<std::vector<std::string>> rows;  ///< each as long as the header
  [[nodiscard]] bool has_header() const {
    return std::any_of(header.begin(), header.end(), [](const std::string& s) { return !s.empty(); });
  }
};

struct Block {
  enum class Kind { Section, Paragraph, Table, Picture, Template };
  Kind kind = Kind::Paragraph;
  std::string id;    ///< Section: the HTML id
  std::string text;  ///< Section: its heading; Paragraph: the text; Picture, Template: caption
  Table table;
  render::Image image;
  render::VectorPage page;  ///< Template: the 1:1 page
};

std::string signed_percent(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%+.1f %%", v);
  return buf;
}

double number_at(const json& j, const char* key, double fallback = std::nan("")) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

std::string string_at(const json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : std::string();
}

struct Document {
  std::vector<Block> blocks;
  void section(std::string id, std::string heading) {
    Block b;
    b.kind = Block::Kind::Section;
    b.id = std::move(id);
    b.text = std::move(heading);
    blocks.push_back(std::move(b));
  }
  void paragraph(std::string text) {
    Block b;
    b.text = std::move(text);
    blocks.push_back(std::move(b));
  }
  void table(Table t) {
    Block b;
    b.kind = Block::Kind::Table;
    b.table = std::move(t);
    blocks.push_back(std::move(b));
  }
  void picture(render::Image image, std::string caption) {
    Block b;
    b.kind = Block::Kind::Picture;
    b.image = std::move(image);
    b.text = std::move(caption);
    blocks.push_back(std::move(b));
  }
  void template_page(render::VectorPage page, std::string caption) {
    Block b;
    b.kind = Block::Kind::Template;
    b.page = std::move(page);
    b.text = std::move(caption);
    blocks.push_back(std::move(b));
  }
};

// ---- Sections -----------------------------------------------------------------------------

void reproduce_section(Document& d, const PlanReportSource& s) {
  d.section("reproduce", "Session and program");
  Table t;
  t.header = {"", ""};
  t.rows.push_back({"Session file", s.session_file.generic_string()});
  t.rows.push_back({"SHA-256", s.session_sha256});
  t.rows.push_back({"Size", std::to_string(s.session_bytes) + " bytes"});
  t.rows.push_back({"Program", s.program});
  t.rows.push_back({"Compute threads", std::to_string(s.openmp_threads) + " (OpenMP), " +
                                           std::to_string(s.blas_threads) + " (BLAS)"});
  d.table(std::move(t));
  d.paragraph("To reproduce: check the file with sha256sum, then run sutura replay " +
              s.session_file.filename().string() + " --threads " + std::to_string(s.openmp_threads) +
              " with this program. The same build and thread count give bit-identical shapes "
              "(report.json lists each object's position hash).");
}

void plan_section(Document& d, const Plan& plan) {
  d.section("plan", "Plan steps");
  if (plan.applied == 0) {
    d.paragraph("No step of the plan is in effect.");
    return;
  }
  Table t;
  t.header = {"#", "Line", "Step", "Note"};
  for (std::size_t i = 0; i < plan.applied; ++i) {
    const PlanStep& p = plan.steps[i];
    t.rows.push_back({std::to_string(i + 1), std::to_string(p.line), describe_action(p.source),
                      string_at(p.source, "note")});
  }
  d.table(std::move(t));
  if (plan.steps.size() > plan.applied)
    d.paragraph(std::to_string(plan.steps.size() - plan.applied) +
                " later step(s) were undone and are not part of this plan.");
}

void views_section(Document& d, const SnapshotDrawer& draw, int width, int height, const std::string& before) {
  d.section("views", "Before and after");
  d.paragraph("Each object before the operation (left) and now (right), from the standard views of "
              "the workspace frame (+x the patient's left, +y posterior, +z superior; docs/anatomy.md). "
              "Sutures are green, incisions red. " + before);
  struct View {
    const char* name;
    Vec3d view;
  };
  static constexpr std::array<View, 3> kViews = {{{"Anterior", {0.0, 1.0, 0.0}},
                                                  {"Left lateral", {-1.0, 0.0, 0.0}},
                                                  {"Posterior", {0.0, -1.0, 0.0}}}};
  for (const View& v : kViews) {
    SnapshotOp op;
    op.width = width;
    op.height = height;
    op.side_by_side = true;
    op.camera.view = v.view;
    d.picture(draw(op), std::string(v.name) + " view: before | after");
  }
}

bool is_profile(const json& m) {
  return m.is_object() && m.contains("before") && m["before"].is_object() && m["before"].contains("stations") &&
         m.contains("after") && m["after"].is_object();
}

void lumen_section(Document& d, const json& measurements) {
  d.section("lumen", "Lumen profile");
  bool any = false;
  for (const auto& [name, m] : measurements.items()) {
    if (!is_profile(m)) continue;
    any = true;
    render::Chart chart;
    chart.width = 960;
    chart.height = 480;
    chart.title = "Lumen '" + name + "' of '" + string_at(m, "object") + "'";
    chart.x_label = "arc length along the centreline (mm)";
    chart.y_label = "cross-section area (mm2)";
    for (const char* side : {"before", "after"}) {
      render::ChartSeries series;
      series.label = side;
      if (side[0] == 'a') series.color = {214, 39, 40, 255};
      const json stations = m.contains(side) ? m[side].value("stations", json::array()) : json::array();
      for (const json& st : stations) {
        const double x = number_at(st, "arc_length_mm"), y = number_at(st, "area_mm2");
        if (st.value("closed", false) && std::isfinite(x) && std::isfinite(y)) series.points.push_back({x, y});
      }
      if (!series.points.empty()) chart.series.push_back(std::move(series));
    }
    if (chart.series.empty()) continue;
    const double after_min = m.contains("after") ? number_at(m["after"], "min_area_arc_length_mm") : std::nan("");
    if (std::isfinite(after_min)) chart.markers.push_back({after_min, "narrowest now"});
    d.picture(render::draw_chart(chart),
              "Lumen '" + name + "': cross-section area along the centreline, before and after "
              "(stations where the section is not closed are left out)");
  }
  if (!any) d.paragraph("No lumen profile was measured (a measure op along a centreline).");
}

void change_row(Table& t, const std::string& name, const std::string& quantity, double before, double after,
                int decimals) {
  const bool both = std::isfinite(before) && std::isfinite(after);
  t.rows.push_back({name, quantity, std::isfinite(before) ? fixed(before, decimals) : "-",
                    std::isfinite(after) ? fixed(after, decimals) : "-",
                    both && before != 0.0 ? signed_percent(100.0 * (after - before) / before) : "-"});
}

// Whether the step names `object` (its "object", or a solve's "objects", none meaning all).
bool names_object(const json& src, const std::string& object) {
  if (src.contains("objects") && src["objects"].is_array()) {
    for (const json& o : src["objects"])
      if (o.is_string() && o.get<std::string>() == object) return true;
    return false;
  }
  return !src.contains("object") || string_at(src, "object") == object;
}

// What "before" is for each object: the pre-operative vessel under its loads (a solve made it
// the pre-operative shape, or an imaged vessel was unloaded), or unloaded; and a warning when
// it is unloaded while the plan loads the vessel, so that before and after differ by the
// loading as well as by the surgery.
std::string before_note(const Plan& plan, const Workspace& workspace) {
  std::string note;
  for (const SceneObject& obj : workspace.objects()) {
    int loaded_before = 0;
    bool loads = false;
    for (std::size_t i = 0; i < plan.applied; ++i) {
      const PlanStep& p = plan.steps[i];
      if (!names_object(p.source, obj.name)) continue;
      if ((p.op == "solve" && p.source.value("as_before", false)) || p.op == "unload") loaded_before = p.line;
      if (p.op == "pressure" || p.op == "force" || p.op == "line_load" || p.op == "body_force") loads = true;
    }
    std::string line = "'" + obj.name + "': ";
    if (loaded_before > 0)
      line += "before is the pre-operative vessel under its loads (line " + std::to_string(loaded_before) + ").";
    else if (loads)
      line += "before is the vessel unloaded, as it was loaded or generated, while after is under the plan's loads: "
              "each change includes the loading as well as the surgery. To compare like with like, make the "
              "loaded vessel the pre-operative shape (a solve with as_before before the first incision).";
    else
      line += "before is the vessel as it was loaded or generated; nothing loads it.";
    if (!note.empty()) note += ' ';
    note += line;
  }
  return note;
}

void measurements_section(Document& d, const json& measurements, const json& checks, const std::string& before) {
  d.section("measurements", "Measurements");
  if (measurements.empty()) {
    d.paragraph("No measurement was taken.");
  } else {
    Table t;
    t.header = {"Measurement", "Quantity", "Before", "After", "Change"};
    for (const auto& [name, m] : measurements.items()) {
      if (is_profile(m)) {
        const json &b = m["before"], &a = m["after"];
        change_row(t, name, "smallest lumen area (mm2)", number_at(b, "min_area_mm2"), number_at(a, "min_area_mm2"), 2);
        change_row(t, name, "its equivalent diameter (mm)", number_at(b, "min_equivalent_diameter_mm"),
                   number_at(a, "min_equivalent_diameter_mm"), 2);
        change_row(t, name, "its position along the centreline (mm)", number_at(b, "min_area_arc_length_mm"),
                   number_at(a, "min_area_arc_length_mm"), 1);
        t.rows.back().back() = "-";  // a position's relative change means nothing
      } else if (m.is_object() && m.contains("before") && m.contains("after")) {  // a plane section
        const json &b = m["before"], &a = m["after"];
        change_row(t, name, "cross-section area (mm2)", number_at(b, "area_mm2"), number_at(a, "area_mm2"), 2);
        change_row(t, name, "equivalent diameter (mm)", number_at(b, "equivalent_diameter_mm"),
                   number_at(a, "equivalent_diameter_mm"), 2);
      } else if (m.is_object() && m.contains("symmetric_mm")) {  // a distance between two objects
        t.rows.push_back({name, "Hausdorff distance '" + string_at(m, "a") + "' to '" + string_at(m, "b") + "' (mm)",
                          "-", fixed(number_at(m, "symmetric_mm"), 3), "-"});
      }
    }
    d.table(std::move(t));
    d.paragraph("Before: the pre-operative shape; after: the shape now. " + before);
  }
  if (checks.empty()) return;
  Table c;
  c.header = {"Check", "Quantity", "Value", "Expected", "Result"};
  for (const json& k : checks) {
    std::string what = !string_at(k, "measurement").empty() ? "measurement '" + string_at(k, "measurement") + "'"
                       : !string_at(k, "object").empty()    ? "object '" + string_at(k, "object") + "'"
                                                            : "probe '" + string_at(k, "probe") + "'";
    const std::string expected =
        k.contains("min") ? "[" + general(number_at(k, "min")) + ", " + general(number_at(k, "max")) + "]"
                          : general(number_at(k, "expected")) + " +- " + general(number_at(k, "allowed_error"));
    c.rows.push_back({what, string_at(k, "quantity"), general(number_at(k, "value")), expected,
                      k.value("pass", false) ? "pass" : "FAIL"});
  }
  d.table(std::move(c));
}

void equilibrium_section(Document& d, const Plan& plan) {
  d.section("equilibrium", "Equilibrium");
  Table t;
  t.header = {"Line", "Step", "Status"};
  for (std::size_t i = 0; i < plan.applied; ++i) {
    const PlanStep& p = plan.steps[i];
    if (p.op != "solve" && p.op != "simulate" && p.op != "unload" && p.op != "design_patch") continue;
    const json& r = p.result;
    std::string status;
    const auto add = [&status](const std::string& part) {
      if (part.empty()) return;
      if (!status.empty()) status += "; ";
      status += part;
    };
    if (p.op == "design_patch") add(string_at(r, "summary"));
    if (r.contains("converged") && r["converged"].is_boolean())
      add(r["converged"].get<bool>() ? "converged" : "NOT converged");
    if (const double s = number_at(r, "s_reached"); std::isfinite(s)) add("relaxed to s = " + general(s));
    if (const double res = number_at(r, "residual"); std::isfinite(res)) add("residual " + general(res) + " N");
    if (r.contains("equilibrium")) add(string_at(r["equilibrium"], "summary"));
    add(string_at(r, "warning"));
    if (status.empty()) status = "no equilibrium was computed (dynamics)";
    t.rows.push_back({std::to_string(p.line), describe_action(p.source), status});
  }
  if (t.rows.empty()) {
    d.paragraph("No solve or simulation is part of the plan: the shapes shown are not equilibria.");
    return;
  }
  d.table(std::move(t));
}

void design_section(Document& d, const Plan& plan) {
  bool any = false;
  for (std::size_t i = 0; i < plan.applied; ++i) {
    const PlanStep& p = plan.steps[i];
    if (p.op != "design_patch") continue;
    if (!any) d.section("design", "Patch design");
    any = true;
    const json& r = p.result;
    d.paragraph("Line " + std::to_string(p.line) + ": " + string_at(r, "status") + ", width " +
                fixed(number_at(r, "width_mm"), 2) + " mm after " +
                std::to_string(r.value("relaxations", 0)) + " relaxations. " + string_at(r, "reason"));
    Table t;
    t.header = {"Width (mm)", "Smallest area (mm2)", "Coarctation index", "Bulge", "Meets target", "Within limits"};
    for (const json& c : r.value("candidates", json::array()))
      t.rows.push_back({fixed(number_at(c, "width_mm"), 3), fixed(number_at(c, "min_area_mm2"), 2),
                        fixed(number_at(c, "coarctation_index"), 3), fixed(number_at(c, "bulge"), 3),
                        c.value("meets_target", false) ? "yes" : "no", c.value("within_limits", false) ? "yes" : "no"});
    d.table(std::move(t));
    try {
      d.picture(render::draw_chart(design_chart(r)),
                "Line " + std::to_string(p.line) + ": the quantity sized and the bulge against the patch's width, the "
                "target band green, the bulge limit red");
    } catch (const std::invalid_argument& e) {
      d.paragraph(std::string("No plot: ") + e.what());
    }
  }
  if (!any) {
    d.section("design", "Patch design");
    d.paragraph("No patch was designed to a target (design_patch).");
  }
}

// The last step in effect that sewed in the patch whose material is `material` (a patch or
// design_patch whose result names it), or none: a material step over the whole object, for
// one, makes every face the wall's, and a later patch may take the index again.
const PlanStep* patch_step(const Plan& plan, const std::string& object, int material) {
  const PlanStep* found = nullptr;
  for (std::size_t i = 0; i < plan.applied; ++i) {
    const PlanStep& p = plan.steps[i];
    if ((p.op == "patch" || p.op == "design_patch") && string_at(p.source, "object") == object &&
        p.result.is_object() && p.result.value("material_index", -1) == material)
      found = &p;
  }
  return found;
}

// Where that step started the patch (its `start`, or its `patch` part's), the template's
// proximal end.
std::optional<engine::Vec3> patch_start(const PlanStep* step) {
  if (step == nullptr) return std::nullopt;
  const json& src = step->source;
  const json& fields = step->op == "design_patch" && src.contains("patch") ? src["patch"] : src;
  if (!fields.is_object() || !fields.contains("start") || !fields["start"].is_array() || fields["start"].size() != 3)
    return std::nullopt;
  const json& p = fields["start"];
  for (const json& c : p)
    if (!c.is_number()) return std::nullopt;
  return engine::Vec3(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
}

void template_section(Document& d, const PlanReportSource& s, json& templates) {
  d.section("template", "Patch templates");
  for (const SceneObject& obj : s.workspace->objects()) {
    const std::vector<int> patches = patch_materials(obj);
    for (std::size_t k = 0; k < patches.size(); ++k) {
      const int number = static_cast<int>(k) + 1;
      PatchTemplateOptions options;
      options.patch = number;
      const std::optional<engine::Vec3> start = patch_start(patch_step(*s.plan, obj.name, patches[k]));
      if (start) options.proximal = *start;
      const std::string heading = "Sutura cutting template: " + s.session_file.filename().string() +
                                  ", object '" + obj.name + "', patch " + std::to_string(number);
      const std::string name = "Patch " + std::to_string(number) + " of '" + obj.name + "'";
      PatchTemplate t;
      try {
        t = make_patch_template(obj, heading, options);
      } catch (const std::exception& e) {
        d.paragraph(name + ": no template (" + e.what() + ").");
        templates.push_back({{"object", obj.name}, {"patch", number}, {"error", e.what()}});
        continue;
      }
      std::string text = name + ": " + fixed(t.length_mm, 1) + " x " + fixed(t.width_mm, 1) + " mm, seam " +
                         fixed(t.seam_length_mm, 1) + " mm, area " + fixed(t.area_mm2, 1) + " mm2, " +
                         std::to_string(t.bites) + " bite marks; the rest shape is " + fixed(t.max_gap_mm, 3) +
                         " mm from a flat cut. ";
      text += start ? "Its top is the seam's point nearest where the patch step started."
                    : "No patch step of the plan gives its proximal end: the top of the page is arbitrary.";
      d.paragraph(text);
      d.template_page(t.page, "Cutting template, patch " + std::to_string(number) + " of '" + obj.name + "'");
      templates.push_back({{"object", obj.name}, {"patch", number}, {"seam_length_mm", t.seam_length_mm},
                           {"area_mm2", t.area_mm2}});
    }
  }
  if (templates.empty()) d.paragraph("No patch is sewn in.");
}

void materials_section(Document& d, const PlanReportSource& s) {
  d.section("materials", "Materials");
  Table t;
  t.header = {"Object", "Material", "E (MPa)", "Poisson ratio", "Thickness (mm)", "Faces", "Source"};
  for (const SceneObject& obj : s.workspace->objects()) {
    std::vector<std::size_t> faces(obj.sim.materials.size(), 0);
    for (int m : obj.sim.face_material)
      if (m >= 0 && static_cast<std::size_t>(m) < faces.size()) ++faces[static_cast<std::size_t>(m)];
    const std::vector<int> patches = patch_materials(obj);
    for (std::size_t m = 0; m < obj.sim.materials.size(); ++m) {
      if (faces[m] == 0) continue;
      const engine::ShellMaterial& mat = obj.sim.materials[m];
      const auto it = std::find(patches.begin(), patches.end(), static_cast<int>(m));
      std::string role = m == 0 ? "wall" : it != patches.end() ? "patch " + std::to_string(it - patches.begin() + 1)
                                                                : "part " + std::to_string(m);
      // The source: for the wall, the last step in effect that set the material of the whole
      // object or of its wall; for a patch, the step that sewed it in (patch_step); then each
      // later material step at a point, which may have changed it.
      std::string source = "default values (no step set them)", may;
      const PlanStep* sewn = m == 0 ? nullptr : patch_step(*s.plan, obj.name, static_cast<int>(m));
      for (std::size_t i = 0; i < s.plan->applied; ++i) {
        const PlanStep& p = s.plan->steps[i];
        const json& src = p.source;
        if (string_at(src, "object") != obj.name) continue;
        if (p.op == "material" && src.contains("at")) {
          may += (may.empty() ? "; may have been changed by line " : ", line ") + std::to_string(p.line);
          continue;
        }
        const bool sets = p.op == "material" ? m == 0 : &p == sewn;
        if (!sets) continue;
        source = "line " + std::to_string(p.line) + ": " + describe_action(src);
        if (const std::string note = string_at(src, "note"); !note.empty()) source += " (" + note + ")";
        may.clear();
      }
      source += may;
      t.rows.push_back({obj.name, role, general(mat.youngs_modulus), general(mat.poisson_ratio), general(mat.thickness),
                        std::to_string(faces[m]), source});
    }
  }
  if (t.rows.empty()) {
    d.paragraph("No object.");
    return;
  }
  d.table(std::move(t));
}

// ---- HTML -----------------------------------------------------------------------------------

// Text for the HTML, which is also XML: markup characters escaped, and what is not a valid
// XML character in UTF-8 (control bytes, malformed or overlong sequences, surrogates,
// U+FFFE and U+FFFF; a file name may be any bytes) replaced by U+FFFD.
std::string escaped(const std::string& text) {
  static constexpr const char* kReplacement = "\xEF\xBF\xBD";
  std::string out;
  out.reserve(text.size());
  const auto byte = [&text](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = byte(i);
    if (c < 0x80) {
      switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c < 32 && c != '\n' && c != '\t' && c != '\r' ? kReplacement : std::string(1, char(c));
      }
      ++i;
      continue;
    }
    // A multi-byte sequence: its length from the lead byte, each continuation 10xxxxxx, the
    // code point in range for its length.
    const std::size_t n = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? (c <= 0xEF ? 3 : 0) : c >= 0xC2 && c <= 0xDF ? 2 : 0;
    std::uint32_t cp = n == 2 ? c & 0x1Fu : n == 3 ? c & 0x0Fu : c & 0x07u;
    bool ok = n > 0 && i + n <= text.size();
    for (std::size_t k = 1; ok && k < n; ++k) {
      ok = (byte(i + k) & 0xC0) == 0x80;
      cp = (cp << 6) | (byte(i + k) & 0x3Fu);
    }
    ok = ok && !(n == 3 && cp < 0x800) && !(n == 4 && (cp < 0x10000 || cp > 0x10FFFF)) &&
         !(cp >= 0xD800 && cp <= 0xDFFF) && cp != 0xFFFE && cp != 0xFFFF;
    if (ok) {
      out.append(text, i, n);
      i += n;
    } else {
      out += kReplacement;
      ++i;
    }
  }
  return out;
}

std::string to_html(const Document& d, const std::string& title) {
  std::string h =
      "<!DOCTYPE html>\n<html xmlns=\"http://www.w3.org/1999/xhtml\" lang=\"en\">\n<head>\n"
      "<meta charset=\"utf-8\"/>\n<title>";
  h += escaped(title);
  h += "</title>\n<style>\n"
       "body { font-family: Helvetica, Arial, sans-serif; max-width: 190mm; margin: 12mm auto; color: #111; }\n"
       "h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #999; }\n"
       "table { border-collapse: collapse; margin: 0.6em 0; font-size: 0.9em; }\n"
       "th, td { border: 1px solid #bbb; padding: 0.2em 0.5em; text-align: left; vertical-align: top; }\n"
       "figure { margin: 0.8em 0; } figure img { max-width: 100%; height: auto; } figcaption { font-size: 0.85em; color: #444; }\n"
       "section.template svg { display: block; }\n"
       "@media print { section { break-inside: auto; } figure { break-inside: avoid; } }\n"
       "</style>\n</head>\n<body>\n<h1>";
  h += escaped(title);
  h += "</h1>\n";
  bool open = false;
  for (const Block& b : d.blocks) {
    switch (b.kind) {
      case Block::Kind::Section:
        if (open) h += "</section>\n";
        h += "<section id=\"" + b.id + "\" class=\"" + b.id + "\">\n<h2>" + escaped(b.text) + "</h2>\n";
        open = true;
        break;
      case Block::Kind::Paragraph:
        h += "<p>" + escaped(b.text) + "</p>\n";
        break;
      case Block::Kind::Table: {
        h += "<table>\n";
        if (b.table.has_header()) {
          h += "<thead><tr>";
          for (const std::string& c : b.table.header) h += "<th>" + escaped(c) + "</th>";
          h += "</tr></thead>\n";
        }
        h += "<tbody>\n";
        for (const auto& row : b.table.rows) {
          h += "<tr>";
          for (const std::string& c : row) h += "<td>" + escaped(c) + "</td>";
          h += "</tr>\n";
        }
        h += "</tbody>\n</table>\n";
        break;
      }
      case Block::Kind::Picture:
        h += "<figure><img src=\"";
        h += render::png_data_uri(b.image);
        h += "\" width=\"" + std::to_string(b.image.width) + "\" height=\"" + std::to_string(b.image.height) +
             "\" alt=\"" + escaped(b.text) + "\"/><figcaption>" + escaped(b.text) + "</figcaption></figure>\n";
        break;
      case Block::Kind::Template: {
        std::string svg = render::to_svg(b.page);
        if (svg.rfind("<?xml", 0) == 0) svg.erase(0, svg.find('\n') + 1);  // not allowed inside a document
        h += "<figure>" + svg + "<figcaption>" + escaped(b.text) +
             ", drawn in mm at 1:1; to cut from it, print the PDF's template page at 100 % and check its 10 mm "
             "bar</figcaption></figure>\n";
        break;
      }
    }
  }
  if (open) h += "</section>\n";
  h += "</body>\n</html>\n";
  return h;
}

// ---- PDF ------------------------------------------------------------------------------------

constexpr double kPageWidth = 210.0, kPageHeight = 297.0, kMargin = 18.0;
constexpr double kBody = 3.3, kSmall = 2.9, kHeading = 4.8, kTitle = 6.5;  // font sizes, mm
constexpr double kLeading = 1.35;  // line height / font size

// Words of `text` broken into lines no wider than `width` mm at `size`; a word wider than
// the line is cut by characters. O(characters): widths are summed as the text is read.
std::vector<std::string> wrapped(const std::string& text, double size, double width) {
  std::vector<std::string> lines;
  std::string line;
  double line_width = 0.0;
  const double space = render::text_width_mm(" ", size);
  std::size_t i = 0;
  while (i <= text.size()) {
    std::size_t end = text.find(' ', i);
    if (end == std::string::npos) end = text.size();
    // The word, cut into pieces that each fit a line.
    std::size_t from = i;
    while (from < end) {
      std::size_t to = from;
      double piece = 0.0;
      while (to < end) {
        const double w = render::text_width_mm(std::string(1, text[to]), size);
        if (to > from && piece + w > width) break;
        piece += w;
        ++to;
      }
      const bool whole_word = from == i && to == end;
      if (!line.empty() && (!whole_word || line_width + space + piece > width)) {
        lines.push_back(std::move(line));
        line.clear();
        line_width = 0.0;
      }
      if (!line.empty()) {
        line += ' ';
        line_width += space;
      }
      line.append(text, from, to - from);
      line_width += piece;
      from = to;
    }
    i = end + 1;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

// Text for the PDF's Helvetica (ASCII): the non-ASCII characters the program's own texts use
// are spelled out; other bytes print as '?'.
std::string ascii(const std::string& text) {
  static const std::array<std::pair<const char*, const char*>, 8> kSpelled = {{{"\xC2\xB2", "2"},       // superscript 2
                                                                           {"\xCE\xBD", "nu"},      // nu
                                                                           {"\xC3\x97", "x"},       // times
                                                                           {"\xC2\xB0", " deg"},    // degree
                                                                           {"\xE2\x80\x93", "-"},   // en dash
                                                                           {"\xE2\x80\x94", "-"},   // em dash
                                                                           {"\xCE\xBC", "u"},       // mu
                                                                           {"\xE2\x80\xA6", "..."}}};  // ellipsis
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    bool spelled = false;
    for (const auto& [from, to] : kSpelled) {
      const std::size_t n = std::char_traits<char>::length(from);
      if (text.compare(i, n, from) == 0) {
        out += to;
        i += n;
        spelled = true;
        break;
      }
    }
    if (!spelled) {
      const char c = text[i++];
      out += c == '\n' || c == '\t' || c == '\r' ? ' ' : c;
    }
  }
  return out;
}

class PageWriter {
 public:
  explicit PageWriter(std::string footer) : footer_(std::move(footer)) { new_page(); }

  void title(const std::string& text) { lines(text, kTitle, 0.0, 2.0); }

  /// `keep`: the height (mm) of what follows, kept on the heading's page when it fits on one.
  void heading(const std::string& text, double keep) {
    if (y_ + 3.0 + 2.0 * kHeading + std::min(keep, 120.0) > bottom()) new_page();
    y_ += 3.0;
    lines(text, kHeading, 0.0, 1.0);
    rule(kMargin, kPageWidth - kMargin, y_ - 0.6, 0.3);
    y_ += 1.5;
  }

  void paragraph(const std::string& text, double size = kBody) {
    lines(text, size, 0.0, 1.5);
  }

  void table(const Table& t) {
    const std::size_t columns = t.header.size();
    const double available = kPageWidth - 2.0 * kMargin, pad = 1.2;
    // Natural widths: the widest cell (header included) of each column. When they do not fit,
    // the columns narrower than an equal share of what is left keep theirs and the others
    // share the rest equally (and wrap).
    std::vector<double> width(columns, 6.0);
    for (std::size_t c = 0; c < columns; ++c) {
      width[c] = std::max(width[c], render::text_width_mm(ascii(t.header[c]), kSmall) + 2.0 * pad);
      for (const auto& row : t.rows)
        width[c] = std::max(width[c], render::text_width_mm(ascii(row[c]), kSmall) + 2.0 * pad);
    }
    double natural = 0.0;
    for (double w : width) natural += w;
    std::vector<bool> fixed_width(columns, natural <= available);
    for (std::size_t round = 0; round < columns; ++round) {
      double left = available;
      std::size_t open = 0;
      for (std::size_t c = 0; c < columns; ++c) {
        if (fixed_width[c]) left -= width[c];
        else ++open;
      }
      if (open == 0) break;
      const double share = left / static_cast<double>(open);
      bool changed = false;
      for (std::size_t c = 0; c < columns; ++c)
        if (!fixed_width[c] && width[c] <= share) {
          fixed_width[c] = true;
          changed = true;
        }
      if (!changed) {
        for (std::size_t c = 0; c < columns; ++c)
          if (!fixed_width[c]) width[c] = share;
        break;
      }
    }
    y_ += 1.0;
    if (t.has_header()) row(t.header, width, pad, true);
    for (const auto& r : t.rows) row(r, width, pad, false);
    y_ += 2.0;
  }

  /// The size (mm) a picture takes on the page: the line's width, at most 120 mm high.
  static std::array<double, 2> picture_size(const render::Image& image) {
    const double available = kPageWidth - 2.0 * kMargin;
    double w = available, h = w * image.height / image.width;
    constexpr double kMaxHeight = 120.0;
    if (h > kMaxHeight) {
      w *= kMaxHeight / h;
      h = kMaxHeight;
    }
    return {w, h};
  }

  void picture(const render::Image& image, const std::string& caption) {
    const auto [w, h] = picture_size(image);
    const double caption_height = kLeading * kSmall * 2.0 + 2.0;
    if (y_ + h + caption_height > bottom()) new_page();
    pages_.back().images.push_back({{kMargin, y_}, w, h, image});
    y_ += h + 1.5;
    lines(caption, kSmall, 0.0, 2.0);
  }

  /// The pages with "page i of n" in the footer.
  std::vector<render::VectorPage> finish(const std::vector<render::VectorPage>& appended) {
    std::vector<render::VectorPage> all = pages_;
    all.insert(all.end(), appended.begin(), appended.end());
    const std::size_t n = all.size();
    for (std::size_t i = 0; i < n; ++i)
      all[i].labels.push_back({{kMargin, all[i].height_mm - 10.0},
                               footer_ + " - page " + std::to_string(i + 1) + " of " + std::to_string(n), kSmall});
    return all;
  }

 private:
  static double bottom() { return kPageHeight - kMargin; }

  void new_page() {
    pages_.emplace_back();
    pages_.back().width_mm = kPageWidth;
    pages_.back().height_mm = kPageHeight;
    y_ = kMargin;
  }

  void rule(double x0, double x1, double y, double width, double grey = 0.0) {
    render::PageStroke s;
    s.points = {{x0, y}, {x1, y}};
    s.width_mm = width;
    s.grey = grey;
    pages_.back().strokes.push_back(std::move(s));
  }

  void lines(const std::string& text, double size, double indent, double after) {
    for (const std::string& l : wrapped(ascii(text), size, kPageWidth - 2.0 * kMargin - indent)) {
      if (y_ + kLeading * size > bottom()) new_page();
      y_ += kLeading * size;
      pages_.back().labels.push_back({{kMargin + indent, y_ - 0.3 * size}, l, size});
    }
    y_ += after;
  }

  void row(const std::vector<std::string>& cells, const std::vector<double>& width, double pad, bool header) {
    // A row at most a page high: a cell with more lines ends with a line saying so (the HTML
    // has the whole text).
    const auto most = static_cast<std::size_t>((bottom() - kMargin - 2.0) / (kLeading * kSmall)) - 1;
    std::vector<std::vector<std::string>> wrapped_cells;
    std::size_t height = 1;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      // (1e-6 mm of slack: a column as wide as its widest cell keeps that cell on one line.)
      std::vector<std::string> lines = wrapped(ascii(cells[c]), kSmall, width[c] - 2.0 * pad + 1e-6);
      if (lines.size() > most) {
        lines.resize(most);
        lines.back() = "[cut here: the HTML has the whole text]";
      }
      height = std::max(height, lines.size());
      wrapped_cells.push_back(std::move(lines));
    }
    const double h = kLeading * kSmall * static_cast<double>(height) + 1.0;
    if (y_ + h > bottom()) new_page();
    double x = kMargin;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      double y = y_ + 0.5;
      for (const std::string& l : wrapped_cells[c]) {
        y += kLeading * kSmall;
        pages_.back().labels.push_back({{x + pad, y - 0.3 * kSmall}, l, kSmall});
      }
      x += width[c];
    }
    y_ += h;
    rule(kMargin, x, y_, header ? 0.3 : 0.1, header ? 0.0 : 0.6);
  }

  std::string footer_;
  std::vector<render::VectorPage> pages_;
  double y_ = kMargin;
};

std::vector<render::VectorPage> to_pages(const Document& d, const std::string& title) {
  PageWriter w(title);
  w.title(title);
  std::vector<render::VectorPage> templates;
  for (std::size_t i = 0; i < d.blocks.size(); ++i) {
    const Block& b = d.blocks[i];
    switch (b.kind) {
      case Block::Kind::Section: {
        // Keep the heading with a picture that follows it, or with a few lines of anything else.
        double keep = 4.0 * kLeading * kBody;
        if (i + 1 < d.blocks.size() && d.blocks[i + 1].kind == Block::Kind::Picture)
          keep = PageWriter::picture_size(d.blocks[i + 1].image)[1] + 8.0;
        w.heading(b.text, keep);
        break;
      }
      case Block::Kind::Paragraph: w.paragraph(b.text); break;
      case Block::Kind::Table: w.table(b.table); break;
      case Block::Kind::Picture: w.picture(b.image, b.text); break;
      case Block::Kind::Template:
        templates.push_back(b.page);
        w.paragraph(b.text + ": page " + std::to_string(templates.size()) + " of the templates at the end of "
                    "this PDF, at 1:1. Print it at 100 % (no fitting to the page) and check its 10 mm bar.");
        break;
    }
  }
  return w.finish(templates);
}

}  // namespace

PlanReport make_plan_report(const PlanReportSource& s, const SnapshotDrawer& draw, int view_width, int view_height) {
  if (s.plan == nullptr || s.measurements == nullptr || s.checks == nullptr || s.workspace == nullptr || !draw)
    throw std::invalid_argument("plan report: an input is missing");
  for (int v : {view_width, view_height})
    if (v < 200 || v > 2000) throw std::invalid_argument("plan report: a view's size must be in [200, 2000] pixels");
  Document d;
  json templates = json::array();
  reproduce_section(d, s);
  if (!s.description.empty()) d.paragraph(s.description);
  plan_section(d, *s.plan);
  const std::string before = before_note(*s.plan, *s.workspace);
  views_section(d, draw, view_width, view_height, before);
  lumen_section(d, *s.measurements);
  measurements_section(d, *s.measurements, *s.checks, before);
  equilibrium_section(d, *s.plan);
  design_section(d, *s.plan);
  template_section(d, s, templates);
  materials_section(d, s);

  const std::string title = "Sutura plan report: " + s.session_file.filename().string();
  PlanReport r;
  r.html = to_html(d, title);
  const std::vector<render::VectorPage> pages = to_pages(d, title);
  r.pdf = render::to_pdf(pages, title);
  json sections = json::array();
  std::size_t pictures = 0;
  for (const Block& b : d.blocks) {
    if (b.kind == Block::Kind::Section) sections.push_back(b.id);
    if (b.kind == Block::Kind::Picture) ++pictures;
  }
  r.summary = {{"sections", sections},
               {"pdf_pages", pages.size()},
               {"pictures", pictures},
               {"templates", templates},
               {"session_sha256", s.session_sha256}};
  return r;
}

std::pair<std::string, std::uintmax_t> file_sha256(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read '" + file.string() + "' to hash it");
  sha256_ctx ctx;
  sha256_init(&ctx);
  std::vector<char> buffer(std::size_t(1) << 16);
  std::uintmax_t total = 0;
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    sha256_update(&ctx, n, reinterpret_cast<const std::uint8_t*>(buffer.data()));
    total += n;
  }
  if (in.bad()) throw std::runtime_error("reading '" + file.string() + "' failed while hashing it");
  std::array<std::uint8_t, SHA256_DIGEST_SIZE> digest{};
  sha256_digest(&ctx, digest.size(), digest.data());
  std::string hex;
  for (std::uint8_t b : digest) {
    static constexpr char kHex[] = "0123456789abcdef";
    hex += kHex[b >> 4];
    hex += kHex[b & 15];
  }
  return {hex, total};
}

std::string program_version() { return std::string("sutura ") + SUTURA_VERSION + " (commit " + SUTURA_COMMIT + ")"; }

}  // namespace sutura::app
