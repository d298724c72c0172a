// The Plan section: objects, opening meshes, planning tools, material, undo/redo.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "panels.hpp"
#include "sutura/app/incision_span.hpp"
#include "sutura/app/plan.hpp"
#include "sutura/app/suture_preview.hpp"

namespace sutura::ui {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr double kMpaPerMmHg = 133.322e-6;

void object_list(GuiState& s) {
  const auto& objs = s.controller.workspace().objects();
  if (objs.empty()) {
    ImGui::TextDisabled("No objects yet: open a mesh or generate one.");
    return;
  }
  for (std::size_t i = 0; i < objs.size(); ++i) {
    const auto& o = objs[i];
    const std::string label = o.name + "  (" + std::to_string(o.mesh.num_vertices()) + " vertices, " +
                              std::to_string(o.mesh.num_faces()) + " faces, " +
                              std::to_string(o.mesh.boundary_loops().size()) + " boundary loops)";
    if (ImGui::Selectable(label.c_str(), s.object == i)) s.object = i;
    s.widgets.note("object " + o.name);
  }
}

// File path field with a one-level directory browser and the generators.
void open_controls(GuiState& s) {
  const auto why = s.why_not(Command::OpenMesh);
  ImGui::InputText("name", s.new_object, sizeof s.new_object);
  s.widgets.note("name");
  ImGui::InputText("file", s.open_path, sizeof s.open_path);
  s.widgets.note("file");
  ImGui::SameLine();
  if (ImGui::SmallButton("Browse")) {
    s.browse_dir = fs::absolute(fs::path(s.open_path).has_parent_path()
                                    ? fs::path(s.open_path).parent_path()
                                    : fs::current_path())
                       .lexically_normal()
                       .string();
    ImGui::OpenPopup("browse");
  }
  if (ImGui::BeginPopup("browse")) {
    ImGui::TextUnformatted(s.browse_dir.c_str());
    std::error_code ec;
    if (ImGui::Selectable("..", false, ImGuiSelectableFlags_DontClosePopups))
      s.browse_dir = fs::path(s.browse_dir).parent_path().string();
    std::vector<fs::directory_entry> entries;
    for (const auto& e : fs::directory_iterator(s.browse_dir, ec)) entries.push_back(e);
    std::sort(entries.begin(), entries.end());
    for (const auto& e : entries) {
      const std::string ext = e.path().extension().string();
      const bool dir = e.is_directory(ec);
      if (!dir && ext != ".stl" && ext != ".obj" && ext != ".ply") continue;
      const std::string label = e.path().filename().string() + (dir ? "/" : "");
      if (ImGui::Selectable(label.c_str(), false, dir ? ImGuiSelectableFlags_DontClosePopups : 0)) {
        if (dir) s.browse_dir = e.path().string();
        else std::snprintf(s.open_path, sizeof s.open_path, "%s", e.path().c_str());
      }
    }
    ImGui::EndPopup();
  }
  noted_checkbox(s.widgets, "Segmentation export: prepare it", &s.open_prepare);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("A closed CT/MRI segmentation (flat end caps, dense, noisy): open the caps as "
                      "named ends, keep the largest part, smooth and remesh as it loads (the same "
                      "as `sutura prepare`).");
  if (s.open_prepare) {
    ImGui::SetNextItemWidth(90);
    ImGui::InputFloat("target edge, mm (0: auto)", &s.prepare_edge_length, 0.0f, 0.0f, "%.2f");
    s.widgets.note("prepare edge length");
    s.prepare_edge_length = std::max(0.0f, s.prepare_edge_length);
  }
  if (gated_button(s.widgets, "Open mesh", why))
    s.perform(app::load_op(s.new_object, fs::path(s.open_path), s.controller.recorder().file(), s.open_prepare,
                      static_cast<double>(s.prepare_edge_length)),
              (s.open_prepare ? "Prepared " : "Loaded ") + std::string(s.open_path));
  ImGui::SameLine();
  if (gated_button(s.widgets, "Tube", why, "A generated vessel segment (radius 4 mm, 30 mm long)."))
    s.perform(app::generate_op(s.new_object, "tube", {{"radius", 4.0}, {"length", 30.0}}));
  ImGui::SameLine();
  if (gated_button(s.widgets, "Strip", why, "A flat strip 40 x 10 mm in the z = 0 plane."))
    s.perform(app::generate_op(s.new_object, "strip"));
  // The bundled synthetic neonatal anatomy (assets/anatomy, `sutura generate arch`), one
  // click away: the aortic arch with its coarctation, and the pulmonary artery.
  const fs::path anatomy = fs::path(SUTURA_ASSETS_DIR) / "anatomy" / "coarse";
  if (gated_button(s.widgets, "Aortic arch", why,
                   "The bundled neonatal aortic arch with a coarctation (coarse, 4.4k faces), with the "
                   "bundled sessions' neonatal wall: E 1 MPa, nu 0.45, 0.6 mm (Materials of the selected "
                   "object changes it)."))
    // The wall as every bundled arch session has it, recorded as its own step: a loaded mesh
    // otherwise has the engine's default material, 1 mm thick.
    if (s.perform(app::load_op("aorta", anatomy / "aorta.ply", s.controller.recorder().file(), false, 0.0,
                               anatomy / "landmarks.json"),
                  "Loaded the bundled aortic arch"))
      s.perform(app::bundled_arch_wall_op("aorta"),
                "Loaded the bundled aortic arch, with the bundled sessions' neonatal wall: E 1 MPa, nu 0.45, "
                "0.6 mm");
  ImGui::SameLine();
  if (gated_button(s.widgets, "Pulmonary artery", why,
                   "The bundled pulmonary artery beside the arch (coarse)."))
    s.perform(app::load_op("pulmonary", anatomy / "pulmonary.ply", s.controller.recorder().file(), false, 0.0,
                      anatomy / "landmarks.json"),
              "Loaded the bundled pulmonary artery");
}

void tool_choice(GuiState& s) {
  const auto tool_radio = [&](const char* label, Tool t, const std::optional<std::string>& why) {
    ImGui::BeginDisabled(why.has_value());
    if (noted_radio(s.widgets, label, s.tool == t)) s.tool = t;
    ImGui::EndDisabled();
    if (why) tooltip_for_last_item(*why);
    ImGui::SameLine();
  };
  tool_radio("Navigate", Tool::Navigate, std::nullopt);
  tool_radio("Incise", Tool::Incise, s.why_not(Command::Incise, "incise"));
  tool_radio("Suture", Tool::Suture, s.why_not(Command::Suture, "join"));
  ImGui::NewLine();
  tool_radio("Fix ends", Tool::Fix, s.why_not(Command::FixRegion));
  tool_radio("Patch", Tool::Patch, s.why_not(Command::AddPatch, "patch"));
  tool_radio("Remesh", Tool::Remesh, s.why_not(Command::Remesh, "remesh"));
  tool_radio("Resect", Tool::Resect, s.why_not(Command::Resect, "resect"));
  ImGui::NewLine();
}

void incise_controls(GuiState& s) {
  ImGui::TextWrapped("Click points on the surface; Enter commits, Esc cancels. %zu point(s).",
                     s.incision.points.size());
  if (noted_radio(s.widgets, "cut through faces", !s.incision.snap)) s.incision.snap = false;
  ImGui::SameLine();
  if (noted_radio(s.widgets, "snap to edges", s.incision.snap)) s.incision.snap = true;
  const std::optional<std::string> why =
      s.incision.points.size() < 2 ? std::optional<std::string>("Click at least two points.") : std::nullopt;
  if (gated_button(s.widgets, "Commit incision", why)) commit_incision(s);
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) cancel_draft(s);
}

void suture_controls(GuiState& s) {
  static const char* kSteps[] = {"click one end of side A",
                                 "click the other end of side A",
                                 "click one end of side B",
                                 "click the other end of side B",
                                 "both sides chosen: Join (or Enter)"};
  ImGui::TextWrapped("Click the two ends of each side, in either order; each side takes the "
                     "shorter way along the boundary between them, and the surface's orientation "
                     "decides which ends meet (grey lines). The same point twice takes its whole "
                     "loop (an open end, for an end-to-end anastomosis), or, below, from one lip "
                     "of an incision round to the other (a flap). Next: %s.",
                     kSteps[std::min<std::size_t>(s.suture.clicks.size(), 4)]);
  if (const auto* obj = s.selected()) {
    const app::SuturePreview p = app::preview_suture(obj->mesh, s.suture.clicks, s.suture.long_way, s.suture.lip_to_lip);
    for (const auto& line : p.lines) ImGui::TextWrapped("%s", line.c_str());
  }
  noted_checkbox(s.widgets, "Side A the long way round", &s.suture.long_way[0]);
  ImGui::SameLine();
  noted_checkbox(s.widgets, "Side B the long way round", &s.suture.long_way[1]);
  noted_checkbox(s.widgets, "Same point twice: from lip round to lip (flap)", &s.suture.lip_to_lip);
  tooltip_for_last_item(
      "Subclavian flap: click the corner where the subclavian incision meets the aortotomy "
      "twice for side A (the opened artery, lip to rim to lip) and twice for side B (the "
      "aortotomy); 'long way round' swaps the two arcs.");
  noted_checkbox(s.widgets, "Draw side A onto side B (flap)", &s.suture.onto_b);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Side B stays; side A and the tissue behind it follow as rigidly as "
                      "possible. Otherwise both sides meet halfway.");
  const std::optional<std::string> why =
      s.suture.clicks.size() < 4 ? std::optional<std::string>("Pick both chains first.") : std::nullopt;
  if (gated_button(s.widgets, "Join", why)) commit_suture(s);
  ImGui::SameLine();
  if (ImGui::Button("Cancel##suture")) cancel_draft(s);
}

// Brings the patch preview up to date for `op` (nullopt: no patch drafted) on the workspace now.
void refresh_patch_preview(GuiState& s, const std::optional<json>& op) {
  if (!op) {
    s.patch_preview = {};
    s.patch_preview_error.clear();
    s.patch_preview_key.clear();
    return;
  }
  const std::string key = op->dump();
  if (key == s.patch_preview_key && s.patch_preview_revision == s.controller.revision()) return;
  s.patch_preview_key = key;
  s.patch_preview_revision = s.controller.revision();
  s.patch_preview = {};
  s.patch_preview_error.clear();
  try {
    const app::Action action = app::parse_action(*op, s.controller.recorder().file(), s.controller.recorder().lines() + 1);
    s.patch_preview = app::preview_patch(*s.selected(), std::get<app::PatchOp>(action.op),
                                         s.controller.options().limits.faces_per_object);
  } catch (const app::SessionError& e) {
    s.patch_preview_error = e.what();
  } catch (const std::exception& e) {
    s.patch_preview_error = e.what();
  }
}

// mm of lumen measured beyond each end of the incision.
constexpr double kDesignMargin = 3.0;

// Design the width instead of giving it: design_patch with the patch drawn above, relaxed as
// the Simulate panel would, its lumen measured along the incision (app::incision_span). It
// runs in the background like a simulation and ends in Inspect with the chosen patch.
void design_controls(GuiState& s, const std::optional<json>& patch) {
  if (!noted_tree_node(s.widgets, "Design the width to a target")) return;
  ImGui::TextWrapped("Tries widths in the range, each sewn in and relaxed under the loads, until the smallest "
                     "lumen area along the incision (its centreline from 3 mm before the first end clicked to 3 mm "
                     "past the second) reaches the target (docs/patch-design.md).");
  if (noted_radio(s.widgets, "smallest lumen area", !s.patch.target_z_score)) s.patch.target_z_score = false;
  ImGui::SameLine();
  if (noted_radio(s.widgets, "diameter z-score", s.patch.target_z_score)) s.patch.target_z_score = true;
  std::optional<app::DesignZScore> z_target;
  std::optional<std::string> z_refused;
  if (!s.patch.target_z_score) {
    number_field("target area [mm2]", &s.patch.target_area, 1.0f, 2000.0f, 1.0f, "%.1f");
  } else {
    const std::vector<std::string> sites = app::z_score_sites();
    s.patch.site = std::clamp(s.patch.site, 0, static_cast<int>(sites.size()) - 1);
    for (std::size_t i = 0; i < sites.size(); ++i) {
      std::string label = sites[i];
      std::replace(label.begin(), label.end(), '_', ' ');
      if (noted_radio(s.widgets, label, s.patch.site == static_cast<int>(i))) s.patch.site = static_cast<int>(i);
    }
    number_field("z-score", &s.patch.z_score, -5.0f, 5.0f, 0.5f, "%.2f");
    s.widgets.note("z-score");
    number_field("body surface area [m2]", &s.patch.bsa_m2, 0.1f, 2.0f, 0.01f, "%.2f");
    s.widgets.note("body surface area [m2]");
    tooltip_for_last_item("The child's body surface area; the regressions (Pettersen et al. 2008, "
                          "docs/anatomy.md) cover 0.1 to 2 m2.");
    z_target = app::DesignZScore{app::as_typed(s.patch.z_score), sites[static_cast<std::size_t>(s.patch.site)],
                                 app::as_typed(s.patch.bsa_m2)};
    try {
      const double d = app::z_score_diameter_mm(*z_target);
      ImGui::TextWrapped("Target: a diameter of %.2f mm, a lumen area of %.1f mm2.", d, M_PI * d * d / 4.0);
    } catch (const std::exception& e) {
      z_refused = e.what();
    }
  }
  number_field("tolerance [%]", &s.patch.tolerance_percent, 1.0f, 100.0f, 1.0f, "%.0f");
  number_field("narrowest [mm]", &s.patch.width_min, 0.5f, 50.0f, 0.5f, "%.1f");
  number_field("widest [mm]", &s.patch.width_max, 0.5f, 50.0f, 0.5f, "%.1f");
  number_field("max bulge", &s.patch.max_bulge, 1.0f, 3.0f, 0.05f, "%.2f");
  tooltip_for_last_item("The largest lumen diameter along the incision, at most this many times the diameter "
                        "at its second (distal) end.");
  const app::SceneObject* obj = s.selected();
  std::optional<std::string> why = s.why_not(Command::StartSimulation, "design_patch");
  if (!why && !patch) why = "Click both incision ends first.";
  if (!why && !s.patch_preview_error.empty()) why = s.patch_preview_error;
  if (!why && !(s.patch.width_min < s.patch.width_max)) why = "The narrowest width must be below the widest.";
  if (!why && z_refused) why = *z_refused;
  if (gated_button(s.widgets, "Design patch", why,
                   "Runs in the background; ends in Inspect with the chosen width (one undo step).") &&
      patch && obj) {
    app::DesignTarget t;
    t.min_area_mm2 = app::as_typed(s.patch.target_area);
    t.z_score = z_target;
    t.tolerance = app::as_typed(s.patch.tolerance_percent) / 100.0;
    t.width_min = app::as_typed(s.patch.width_min);
    t.width_max = app::as_typed(s.patch.width_max);
    t.max_bulge = app::as_typed(s.patch.max_bulge);
    std::string refused;
    try {
      const app::IncisionSpan span = app::incision_span(obj->mesh, s.patch.ends[0], s.patch.ends[1], kDesignMargin);
      t.centreline = span.centreline;
      t.max_radius = span.max_radius_mm;
    } catch (const std::exception& e) {
      s.error(std::string("design_patch: the lumen along the incision: ") + e.what());
      ImGui::TreePop();
      return;
    }
    if (s.start_run(app::design_patch_op(*patch, s.simulation.relax_steps, s.simulation.collapse_barrier, t), 1, 1,
                    refused)) {
      s.stages.simulation_started();
      s.patch.ends.clear();
      s.tool = Tool::Navigate;
    } else {
      s.error("design_patch: " + refused);
    }
  }
  ImGui::TreePop();
}

void patch_controls(GuiState& s) {
  static const char* kShapes[] = {"ellipse", "diamond", "triangle"};
  static const char* kShapeUse[] = {"an incision inside the wall (patch aortoplasty)", "pointed at both ends",
                                    ("a gusset: apex at the incision's end, base across an opened cut edge "
                                     "(widening)")};
  ImGui::TextUnformatted("shape:");
  for (int k = 0; k < 3; ++k) {
    ImGui::SameLine();
    if (noted_radio(s.widgets, kShapes[k], s.patch.shape == k)) s.patch.shape = k;
    tooltip_for_last_item(kShapeUse[k]);
  }
  number_field("width [mm]", &s.patch.width, 1.0f, 15.0f, 0.5f, "%.1f");
  number_field("patch E [MPa]", &s.patch.youngs_modulus, 0.1f, 200.0f, 0.1f);
  s.widgets.note("patch E [MPa]");
  number_field("patch thickness [mm]", &s.patch.thickness, 0.1f, 2.0f, 0.05f);
  s.widgets.note("patch thickness [mm]");
  ImGui::TextWrapped("Click the two end points of the incision to patch (%zu of 2).",
                     s.patch.ends.size());
  const json material = {{"youngs_modulus", app::as_typed(s.patch.youngs_modulus)},
                         {"poisson_ratio", app::as_typed(s.patch.poisson_ratio)},
                         {"thickness", app::as_typed(s.patch.thickness)}};
  std::optional<json> op;
  if (s.patch.ends.size() == 2 && s.selected())
    op = app::patch_op(s.selected()->name, kShapes[s.patch.shape], s.patch.ends[0], s.patch.ends[1],
                  app::as_typed(s.patch.width), material);
  refresh_patch_preview(s, op);
  if (op && s.patch_preview_error.empty()) {
    ImGui::TextWrapped("The patch as cut, outlined in blue around the incision: %.1f mm wide, %.1f mm long, %.0f mm².",
                       s.patch_preview.width, s.patch_preview.length, s.patch_preview.area);
  } else if (op) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.85f, 0.1f, 0.1f, 1.0f));
    ImGui::TextWrapped("This patch cannot be added: %s", s.patch_preview_error.c_str());
    ImGui::PopStyleColor();
  }
  std::optional<std::string> why;
  if (!op) why = "Click both incision ends first.";
  else if (!s.patch_preview_error.empty()) why = s.patch_preview_error;
  if (gated_button(s.widgets, "Add patch", why) && op) {
    char done[160];
    std::snprintf(done, sizeof done, "Patch added: %s, %.1f mm wide, E %.3g MPa, %.2f mm thick",
                  kShapes[s.patch.shape], s.patch.width, s.patch.youngs_modulus, s.patch.thickness);
    if (s.perform(*op, done)) s.patch.ends.clear();
  }
  design_controls(s, op);
}

void remesh_controls(GuiState& s) {
  ImGui::TextWrapped("Click points on the surface to remesh the faces near the line through "
                     "them (%zu point(s)); none: the whole object. Sutures, material borders, open ends and held "
                     "vertices are kept; the state and rest shape follow.",
                     s.remesh.points.size());
  number_field("radius [mm]", &s.remesh.radius, 0.5f, 20.0f, 0.5f, "%.1f");
  number_field("edge length [mm]", &s.remesh.target_edge_length, 0.0f, 3.0f, 0.05f);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("0: the region's own mean edge length.");
  number_field("grading", &s.remesh.grading, 1.0f, 3.0f, 0.1f);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Growth of the edge length per band away from the clicked points (1 = uniform).");
  number_field("iterations", &s.remesh.iterations, 1, 10);
  if (gated_button(s.widgets, s.remesh.points.empty() ? "Remesh object" : "Remesh region",
                   s.why_not(Command::Remesh, "remesh")) &&
      s.selected()) {
    if (s.perform(app::remesh_op(s.selected()->name, s.remesh.points, app::as_typed(s.remesh.radius),
                                 app::as_typed(s.remesh.target_edge_length), app::as_typed(s.remesh.grading),
                                 s.remesh.iterations),
                  "Remeshed '" + s.selected()->name + "'"))
      s.remesh.points.clear();
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel##remesh")) cancel_draft(s);
  ImGui::Separator();
  ImGui::TextWrapped("Or remesh, in the shape shown, only where a face has an angle below the limit, with the "
                     "faces within the distance along the surface, to the edge length above. A run does this by "
                     "itself and settles again, unless Simulate > Keep triangles well shaped is off.");
  if (const app::SceneObject* o = s.selected())
    for (const app::SmallestAngle& a : s.smallest_angles)
      if (a.object == o->name)
        ImGui::TextWrapped("Smallest angle of '%s' now: %.1f degrees (that face at rest: %.1f), near (%.1f, %.1f, "
                           "%.1f) mm.",
                           a.object.c_str(), a.degrees, a.rest_degrees, a.where.x(), a.where.y(), a.where.z());
  number_field("angle below [deg]", &s.remesh.below_angle, 5.0f, 60.0f, 1.0f, "%.0f");
  number_field("around [mm]", &s.remesh.small_angle_radius, 0.1f, 10.0f, 0.1f, "%.1f");
  // The op's summary is the message: how many faces, or that none was below.
  if (gated_button(s.widgets, "Remesh small angles", s.why_not(Command::Remesh, "remesh")) && s.selected())
    s.perform(app::remesh_small_angles_op(s.selected()->name, app::as_typed(s.remesh.below_angle),
                                          app::as_typed(s.remesh.small_angle_radius),
                                          app::as_typed(s.remesh.target_edge_length), s.remesh.iterations));
}

void load_controls(GuiState& s) {
  number_field("pressure [mmHg]", &s.pressure_mmhg, -120.0f, 120.0f, 5.0f, "%.0f");
  if (gated_button(s.widgets, "Apply pressure", s.why_not(Command::EditMaterial),
                   "Follower pressure on every face, along the face normals; ramped in by the next simulation.") &&
      s.selected())
    s.perform({{"op", "pressure"}, {"object", s.selected()->name},
               {"pressure", s.pressure_mmhg * kMpaPerMmHg}},
              "Pressure of " + std::to_string(int(s.pressure_mmhg)) + " mmHg on '" + s.selected()->name + "'");
  // A vessel meshed at zero pressure (generated, or drawn unloaded): pressurised before the
  // surgery, "before" is that state, so before and after are both under pressure.
  if (gated_button(s.widgets, "Pressurise before surgery", s.why_not(Command::EditMaterial),
                   "The mesh is the vessel at zero pressure: solve it under the pressure applied "
                   "now, and make that pressurised vessel 'before', so that before and after "
                   "compare like with like. Apply the pressure and hold the ends first; before the "
                   "first incision. A segmentation was imaged under pressure: unload it instead.") &&
      s.selected())
    s.perform({{"op", "solve"}, {"objects", {s.selected()->name}}, {"as_before", true},
               {"load_steps", 1}, {"minimize", true}, {"quasi_newton_steps", 5}},
              "'" + s.selected()->name + "' pressurised before surgery: this is 'before'");
  // A segmented vessel was imaged under blood pressure: unload keeps it where it was imaged,
  // stressed by the pressures applied, instead of inflating it a second time.
  if (gated_button(s.widgets, "Imaged under this pressure (unload)", s.why_not(Command::EditMaterial),
                   "The mesh is a vessel as imaged under the pressure applied: find its stress-free "
                   "shape, so that it stays where it is, in equilibrium under that pressure, and "
                   "'before' is the imaged vessel. Apply the pressure and hold the ends first; "
                   "before the first incision.") &&
      s.selected())
    s.perform({{"op", "unload"}, {"object", s.selected()->name}},
              "'" + s.selected()->name + "' unloaded: in equilibrium under its pressure where it was imaged");
}

// What the material fields accept (the session format accepts any E and thickness > 0 and
// nu in [0, 0.5); a region's value outside these is shown in its line and kept unless edited).
constexpr float kMinE = 0.001f, kMaxE = 10000.0f, kMaxNu = 0.499f, kMinThickness = 0.01f, kMaxThickness = 10.0f;

// One region per material of the object: the wall (its first material) and each patch. The
// fields show the chosen region's own values; applying changes that region only.
void material_controls(GuiState& s) {
  const app::SceneObject* obj = s.controller.busy() ? nullptr : s.selected();
  if (!obj) {
    ImGui::TextDisabled("Select an object (not while a simulation runs).");
    return;
  }
  MaterialDraft& d = s.material;
  const std::vector<app::MaterialRegion> regions = app::material_regions(*obj);
  // A patch cut away entirely (a resection) has no faces left: back to the wall.
  if (d.region < 0 || d.region >= int(regions.size()) || (d.region > 0 && regions[std::size_t(d.region)].faces == 0))
    d.region = 0;
  if (d.loaded_object != s.object || d.loaded_region != d.region ||
      d.loaded_revision != s.controller.revision()) {
    const engine::ShellMaterial& m = regions[std::size_t(d.region)].material;
    d.youngs_modulus = float(m.youngs_modulus);
    d.poisson_ratio = float(m.poisson_ratio);
    d.thickness = float(m.thickness);
    d.loaded_object = s.object, d.loaded_region = d.region, d.loaded_revision = s.controller.revision();
    d.youngs_modulus = std::clamp(d.youngs_modulus, kMinE, kMaxE);
    d.poisson_ratio = std::clamp(d.poisson_ratio, 0.0f, kMaxNu);
    d.thickness = std::clamp(d.thickness, kMinThickness, kMaxThickness);
    d.loaded_youngs_modulus = d.youngs_modulus, d.loaded_poisson_ratio = d.poisson_ratio,
    d.loaded_thickness = d.thickness;
  }
  for (std::size_t k = 0; k < regions.size(); ++k) {
    const app::MaterialRegion& r = regions[k];
    if (k > 0 && r.faces == 0) continue;  // a patch undone or cut away
    if (noted_radio(s.widgets, k == 0 ? std::string("Wall") : "Patch " + std::to_string(k), d.region == int(k)))
      d.region = int(k);
    ImGui::SameLine();
    ImGui::TextDisabled("E %.4g MPa, nu %.4g, %.4g mm, %ld faces", r.material.youngs_modulus,
                        r.material.poisson_ratio, r.material.thickness, long(r.faces));
  }
  number_field("E [MPa]", &d.youngs_modulus, kMinE, kMaxE, 0.05f);
  s.widgets.note("E [MPa]");
  number_field("Poisson ratio", &d.poisson_ratio, 0.0f, kMaxNu, 0.01f, "%.3f");
  s.widgets.note("Poisson ratio");
  number_field("thickness [mm]", &d.thickness, kMinThickness, kMaxThickness, 0.05f);
  s.widgets.note("thickness [mm]");
  // Only what was changed is recorded: the region keeps its other values exactly.
  const auto edited = [](float now, float loaded) { return now != loaded ? std::optional<double>(app::as_typed(now)) : std::nullopt; };
  const std::optional<double> e = edited(d.youngs_modulus, d.loaded_youngs_modulus),
                              nu = edited(d.poisson_ratio, d.loaded_poisson_ratio),
                              t = edited(d.thickness, d.loaded_thickness);
  std::optional<std::string> why = s.why_not(Command::EditMaterial);
  if (!why && !e && !nu && !t) why = "Change a value first.";
  const std::string target = d.region == 0 ? "the wall" : "patch " + std::to_string(d.region);
  if (gated_button(s.widgets, d.region == 0 ? "Apply to the wall" : "Apply to this patch", why,
                   d.region == 0 ? "The vessel wall's material; patches keep theirs."
                                 : "This patch's material; the wall and other patches keep theirs.")) {
    const std::string name = obj->name;
    const int region = d.region;
    const ActionOutcome r = s.controller.run(app::material_op(*obj, region, e, nu, t));
    if (!r.ok) {
      s.error(r.op + " failed: " + r.message);
      return;
    }
    // The region's material as it is now (the op's report), all of it: what was changed and
    // what was kept.
    const nlohmann::json& v = r.details.value("values", nlohmann::json::object());
    char values[128];
    std::snprintf(values, sizeof values, ": E %.4g MPa, nu %.4g, %.4g mm", v.value("youngs_modulus", 0.0),
                  v.value("poisson_ratio", 0.0), v.value("thickness", 0.0));
    s.info("Material of " + target + " of '" + name + "' set" + values);
    s.show_warning(r.details);
  }
}

}  // namespace

void plan_section(GuiState& s) {
  if (!s.controller.busy()) object_list(s);
  if (noted_tree_node(s.widgets, "Open or generate")) {
    open_controls(s);
    ImGui::TreePop();
  }
  ImGui::Separator();
  tool_choice(s);
  switch (s.tool) {
    case Tool::Navigate:
      ImGui::TextWrapped("Left drag orbits, right drag pans, wheel zooms, F fits the view.");
      break;
    case Tool::Incise: incise_controls(s); break;
    case Tool::Suture: suture_controls(s); break;
    case Tool::Fix:
      if (noted_radio(s.widgets, "whole loop", !s.fix.run)) s.fix.run = false;
      ImGui::SameLine();
      if (noted_radio(s.widgets, "boundary run", s.fix.run)) s.fix.run = true;
      ImGui::TextWrapped(s.fix.run ? "Click the first and the last boundary vertex of the run "
                                     "(it follows the boundary with the mesh on its left)."
                                   : "Click near a boundary loop (a vessel end) to fix it.");
      if (gated_button(s.widgets, "Hold every open end", s.why_not(Command::FixRegion, "fix")) && s.selected())
        s.perform(app::fix_all_ends_op(s.selected()->name),
                  "Every open end of '" + s.selected()->name + "' held");
      break;
    case Tool::Patch: patch_controls(s); break;
    case Tool::Remesh: remesh_controls(s); break;
    case Tool::Resect: resect_controls(s); break;
  }
  ImGui::Separator();
  if (noted_tree_node(s.widgets, "Materials of the selected object")) {
    material_controls(s);
    ImGui::TreePop();
  }
  if (noted_tree_node(s.widgets, "Loads")) {
    load_controls(s);
    ImGui::TreePop();
  }
  if (gated_button(s.widgets, "Undo", s.why_not(Command::Undo, "undo"), "Ctrl+Z")) undo(s);
  ImGui::SameLine();
  if (gated_button(s.widgets, "Redo", s.why_not(Command::Redo, "redo"), "Ctrl+Y")) redo(s);
  if (noted_tree_node(s.widgets, "Plan steps")) {
    plan_steps(s);
    ImGui::TreePop();
  }
}

void commit_incision(GuiState& s) {
  if (s.tool != Tool::Incise || s.incision.points.size() < 2 || !s.selected()) {
    s.error("An incision needs at least two points on the selected object.");
    return;
  }
  if (s.perform(app::incise_op(s.selected()->name, s.incision.points, s.incision.snap),
                "Incision committed"))
    s.incision.points.clear();
}

void commit_suture(GuiState& s) {
  if (s.tool != Tool::Suture || s.suture.clicks.size() < 4 || !s.selected()) {
    s.error("A suture needs two chains: click both ends of each side.");
    return;
  }
  // Recorded in the boundary direction, so the session says exactly which arcs were joined.
  const auto& mesh = s.selected()->mesh;
  const std::vector<app::ChainEnds> c = app::suture_sides(mesh, s.suture.clicks, s.suture.long_way, s.suture.lip_to_lip);
  std::string done = "Suture joined";
  const app::SuturePreview p = app::preview_suture(mesh, s.suture.clicks, s.suture.long_way, s.suture.lip_to_lip);
  if (p.chains.size() == 2) {
    char buf[160];
    std::snprintf(buf, sizeof buf, " (side A %zu vertices, %.1f mm; side B %zu vertices, %.1f mm)",
                  p.chains[0].size(), p.lengths[0], p.chains[1].size(), p.lengths[1]);
    done += buf;
  }
  if (s.perform(app::join_op(s.selected()->name, c[0], c[1], s.suture.onto_b), done)) {
    s.suture.clicks.clear();
    s.suture.long_way = {false, false};
  }
}

void cancel_draft(GuiState& s) {
  s.fix.clicks.clear();
  s.incision.points.clear();
  s.suture.clicks.clear();
  s.suture.long_way = {false, false};
  s.patch.ends.clear();
  s.remesh.points.clear();
  s.resect.clicks.clear();
}

void undo(GuiState& s) {
  if (auto why = s.why_not(Command::Undo, "undo")) {
    s.error("Undo: " + *why);
    return;
  }
  const app::Plan plan = s.controller.plan();
  s.perform({{"op", "undo"}}, plan.applied == 0 ? std::string("Undone")
                                                : "Undone: " + app::describe_action(plan.steps[plan.applied - 1].source));
}

void redo(GuiState& s) {
  if (auto why = s.why_not(Command::Redo, "redo")) {
    s.error("Redo: " + *why);
    return;
  }
  const app::Plan plan = s.controller.plan();
  s.perform({{"op", "redo"}}, plan.applied >= plan.steps.size()
                                  ? std::string("Redone")
                                  : "Redone: " + app::describe_action(plan.steps[plan.applied].source));
}

}  // namespace sutura::ui
