#include "sutura/app/plan.hpp"

#include <cstdio>

namespace sutura::app {

using nlohmann::json;

namespace {

constexpr double kMmHgInMPa = 0.000133322387415;

std::string number(double v, const char* format = "%g") {
  char buf[48];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

bool has_number(const json& j, const char* key) { return j.contains(key) && j[key].is_number(); }

// 'name' (appended piecewise: GCC 12 warns -Wrestrict, wrongly, on "'" + s + "'").
std::string quoted(const json& name) {
  if (!name.is_string()) return "?";
  std::string out(1, '\'');
  out += name.get_ref<const std::string&>();
  out += '\'';
  return out;
}

std::string quoted(const json& j, const char* key) { return j.contains(key) ? quoted(j[key]) : "?"; }

// "'a'", "'a' and 'b'", "'a', 'b' and 'c'"; "every object" when the list is absent.
std::string object_list(const json& j) {
  if (!j.contains("objects") || !j["objects"].is_array()) return "every object";
  const json& o = j["objects"];
  std::string out;
  for (std::size_t i = 0; i < o.size(); ++i) {
    if (i > 0) out += i + 1 == o.size() ? " and " : ", ";
    out += quoted(o[i]);
  }
  return out.empty() ? "every object" : out;
}

std::string count(const json& j, const char* key, const char* one, const char* many) {
  const std::size_t n = j.contains(key) && j[key].is_array() ? j[key].size() : 0;
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// Which vertices a constraint, force or hold names, in words (docs/session-format.md,
// "Vertex selections").
std::string selection(const json& j) {
  if (j.contains("boundary")) {
    if (j["boundary"].is_string()) return "every open end";
    return count(j, "boundary", "open end", "open ends");
  }
  if (j.contains("boundary_near")) return count(j, "boundary_near", "open end", "open ends");
  if (j.contains("nearest")) return count(j, "nearest", "vertex", "vertices");
  if (j.contains("vertices")) return count(j, "vertices", "vertex", "vertices");
  if (j.contains("box")) return "the vertices in a box";
  if (j.contains("plane")) return "the vertices on a plane";
  return "vertices";
}

std::string material_values(const json& j) {
  std::string out;
  const auto add = [&](const char* key, const std::string& text) {
    if (!has_number(j, key)) return;
    out += (out.empty() ? "" : ", ") + text + number(j[key].get<double>());
  };
  add("youngs_modulus", "E ");
  if (has_number(j, "youngs_modulus")) out += " MPa";
  add("poisson_ratio", "ν ");
  add("thickness", "t ");
  if (has_number(j, "thickness")) out += " mm";
  return out;
}

std::string simulate_text(const json& j) {
  if (!j.contains("relax")) {
    const std::string steps = has_number(j, "steps") ? number(j["steps"].get<double>()) : "100";
    const std::string dt = has_number(j, "dt") ? number(j["dt"].get<double>()) : "0.001";
    return "Run dynamics of " + object_list(j) + ": " + steps + " steps of " + dt + " s";
  }
  const json& r = j["relax"];
  const bool dynamic = r.is_object() && r.value("solver", std::string("static")) == "dynamic";
  std::string out = "Relax " + object_list(j) + " to the repaired shape (" +
                    (dynamic ? "damped dynamics" : "static") + ")";
  if (r.is_object() && has_number(r, "until") && r["until"].get<double>() < 1.0)
    out += ", up to s = " + number(r["until"].get<double>());
  return out;
}

std::string suture_text(const json& j) {
  const std::string on = " on " + quoted(j, "object");
  if (j.contains("sutures") && j["sutures"].is_array() && j["sutures"].size() != 1)
    return std::to_string(j["sutures"].size()) + " sutures" + on;
  const json* chains = nullptr;
  if (j.contains("chains")) chains = &j["chains"];
  else if (j.contains("sutures") && j["sutures"].is_array() && !j["sutures"].empty())
    chains = &j["sutures"][0];
  const auto loop = [](const json& c) { return c.is_object() && c.contains("loop"); };
  if (chains != nullptr && chains->is_array() && chains->size() == 2 && loop((*chains)[0]) && loop((*chains)[1]))
    return "End-to-end anastomosis" + on;
  if (chains != nullptr && chains->is_object() && loop(chains->value("a", json())) && loop(chains->value("b", json())))
    return "End-to-end anastomosis" + on;
  return "Suture" + on;
}

}  // namespace

std::string describe_action(const json& j) {
  const std::string op = j.contains("op") && j["op"].is_string() ? j["op"].get<std::string>() : "?";
  const std::string object = quoted(j, "object");
  if (op == "generate") {
    std::string shape = j.contains("shape") && j["shape"].is_string() ? j["shape"].get<std::string>() : "?";
    for (char& c : shape)
      if (c == '_') c = ' ';
    return j.value("append", false) ? "Add a " + shape + " to " + object
                                    : "Generate a " + shape + " as " + object;
  }
  if (op == "load") {
    const std::string file = j.contains("file") && j["file"].is_string() ? j["file"].get<std::string>() : "?";
    const std::string name = file.substr(file.find_last_of('/') + 1);
    return "Open " + name + " as " + object + (j.contains("prepare") ? ", prepared (segmentation export)" : "");
  }
  if (op == "material") {
    std::string where = j.contains("at") ? "the region at a point"
                        : j.value("region", std::string("all")) == "wall" ? "the wall" : "every face";
    const std::string values = material_values(j);
    return "Material of " + object + ", " + where + (values.empty() ? "" : ": " + values);
  }
  if (op == "fix") return "Hold " + selection(j) + " of " + object;
  if (op == "constrain") return "Constrain " + selection(j) + " of " + object;
  if (op == "force") return "Force on " + selection(j) + " of " + object;
  if (op == "line_load") return "Line load on " + object;
  if (op == "body_force") return "Body force on " + object;
  if (op == "pressure") {
    if (!has_number(j, "pressure")) return "Pressure on " + object;
    const double p = j["pressure"].get<double>();
    return "Pressure of " + number(p / kMmHgInMPa, "%.0f") + " mmHg (" + number(p) + " MPa) on " + object;
  }
  if (op == "solve") {
    if (j.value("as_before", false))
      return "Pressurise " + object_list(j) + " before surgery (static solve: the pre-operative shape)";
    const bool partial = has_number(j, "load_factor") && j["load_factor"].get<double>() < 1.0;
    return "Solve " + object_list(j) + " for equilibrium" +
           (partial ? " up to load factor " + number(j["load_factor"].get<double>()) : std::string());
  }
  if (op == "unload") return "Find the unloaded shape of " + object + " (imaged under pressure)";
  if (op == "simulate") return simulate_text(j);
  if (op == "incise") {
    const bool snap = j.value("mode", std::string("cut")) == "snap";
    return "Incise " + object + " through " + count(j, "points", "point", "points") +
           (snap ? ", snapped to mesh edges" : ", cut through");
  }
  if (op == "join") return suture_text(j);
  if (op == "patch") {
    const std::string shape = j.value("shape", std::string("ellipse"));
    const std::string width = has_number(j, "width") ? number(j["width"].get<double>()) : "4";
    return "Patch into " + object + ": " + (shape == "triangle" ? "gusset" : shape) + ", " + width + " mm wide";
  }
  if (op == "resect") {
    const std::size_t planes = j.contains("planes") && j["planes"].is_array() ? j["planes"].size() : 0;
    if (planes == 1) return "Divide " + object + " at a plane and remove the branch end";
    return "Resect a segment of " + object + (j.value("anastomosis", false) ? " with end-to-end anastomosis" : "");
  }
  if (op == "remesh") {
    std::string out = "Remesh " + object + (j.contains("near") ? " near the given points" : "");
    if (has_number(j, "below_angle"))
      out += " where an angle is below " + number(j["below_angle"].get<double>()) + " degrees";
    if (has_number(j, "target_edge_length"))
      out += " to " + number(j["target_edge_length"].get<double>()) + " mm edges";
    return out;
  }
  if (op == "export_patch_template") return "Cutting template of a patch of " + object;
  if (op == "plan_report") return "Plan report";
  if (op == "design_patch") {
    const json t = j.value("target", json::object());
    const std::string target =
        t.contains("min_area_mm2") && t["min_area_mm2"].is_number()
            ? "a smallest lumen area of " + number(t["min_area_mm2"].get<double>()) + " mm2"
        : t.contains("coarctation_index") && t["coarctation_index"].is_number()
            ? "a coarctation index of " + number(t["coarctation_index"].get<double>())
        : t.contains("z_score") && t["z_score"].is_number()
            ? "a z-score of " + number(t["z_score"].get<double>()) + " at the " +
                  (t.contains("site") && t["site"].is_string() ? t["site"].get<std::string>() : std::string("isthmus"))
            : "a target";
    return "Design a patch for " + object + ": the width that gives " + target;
  }
  if (op == "undo") return "Undo";
  if (op == "redo") return "Redo";
  return op + (j.contains("object") ? " on " + object : std::string());
}

}  // namespace sutura::app
