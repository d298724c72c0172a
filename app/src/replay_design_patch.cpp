// design_patch: the width of a patch chosen so that the repaired lumen meets a target.
//
// Each candidate runs the ops a surgeon would write by hand — patch with that width, the
// simulate run, the measure — from the workspace as design_patch found it, so the chosen
// result is bit for bit what those three ops give (tests/app/test_design_patch.cpp).
//
// The search assumes the measured quantity grows with the width (a wider patch, a wider
// lumen): both ends of the range first, then false position (the Illinois variant: an end
// kept twice has its value halved) aiming at the middle of the accepted band
// [T, T (1 + tolerance)], stopping at the first candidate in the band.
#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <cmath>
#include <numbers>

#include "replay_run.hpp"
#include "design_chart.hpp"
#include "number_text.hpp"
#include "sutura/engine/atomic_file.hpp"
#include "sutura/render/chart.hpp"

namespace sutura::app::detail {

namespace {

struct Candidate {
  double width = 0.0;
  double min_area = 0.0;
  double coarctation_index = 0.0;  // narrowest / distal equivalent diameter
  double bulge = 0.0;              // widest / distal equivalent diameter
  double seconds = 0.0;
  Workspace after;
  json measurement;
  json patch;  // what its patch op reported (material_index, sutures, ...)
  json run;    // what its simulate reported (equilibrium, residual, ...)
};

double diameter(double area) { return 2.0 * std::sqrt(area / std::numbers::pi); }

// The lumen figures of a measure op's result (after the repair).
void read_profile(const json& m, Candidate& c) {
  const json& after = m.at("after");
  c.min_area = after.at("min_area_mm2").get<double>();
  double distal = 0.0, widest = 0.0;
  for (const json& s : after.at("stations"))
    if (s.at("closed").get<bool>() && s.at("area_mm2").is_number()) {
      const double d = diameter(s.at("area_mm2").get<double>());
      distal = d;  // the last closed section along the centreline
      widest = std::max(widest, d);
    }
  c.coarctation_index = diameter(c.min_area) / distal;
  c.bulge = widest / distal;
}

}  // namespace

json Run::execute(const DesignPatchOp& op) {
  const std::filesystem::path plot = op.plot.empty() ? op.plot : output(op.plot);  // refused before any run
  const Workspace start = workspace;  // shares the objects; each candidate starts from it
  const std::vector<Workspace> redo_before = redo_stack;
  remember();                         // the whole design is one step of the undo history
  const std::size_t undo_depth = undo_stack.size();
  const json measurements_before = measurements;
  // A candidate that fails or is stopped leaves the workspace as the op found it.
  auto restore = [&] {
    workspace = start;
    measurements = measurements_before;
    undo_stack.resize(undo_depth - 1);
    redo_stack = redo_before;
  };
  const bool area = op.target == DesignPatchOp::Target::MinArea;
  const std::string quantity = area ? "min_area_mm2" : "coarctation_index";
  const double low_end = op.target_value, high_end = op.target_value * (1.0 + op.tolerance);
  const double aim = 0.5 * (low_end + high_end);

  std::deque<Candidate> candidates;  // evaluate() hands out references: they must stay valid
  auto value = [&](const Candidate& c) { return area ? c.min_area : c.coarctation_index; };
  auto within_limits = [&](const Candidate& c) { return !op.max_bulge || c.bulge <= *op.max_bulge; };
  // Which workspaces are kept (a candidate's objects are full copies): the widest candidate's
  // and the narrowest one's that meets the target within the limits, the only ones the
  // search can still choose besides the one in the band, which ends it.
  Candidate* widest = nullptr;
  Candidate* best = nullptr;
  auto evaluate = [&](double width) -> const Candidate& {
    if (past_deadline()) {
      restore();
      throw std::runtime_error("the time limit came before the candidate " + fixed(width, 3) + " mm wide");
    }
    const auto t0 = std::chrono::steady_clock::now();
    workspace = start;
    PatchOp patch = op.patch;
    patch.params.width = width;
    if (patch.params.min_edge_length > 0.0) patch.params.min_edge_length = width / 5.0;
    json sewn, run;
    try {
      sewn = execute(patch);
      run = execute(op.simulate);
      execute(op.measure);
    } catch (const OpCancelled&) {
      restore();
      throw;
    } catch (const std::exception& e) {
      restore();
      throw std::runtime_error("the candidate " + fixed(width, 3) + " mm wide failed: " + e.what());
    }
    undo_stack.resize(undo_depth);
    Candidate c;
    c.width = width;
    c.measurement = measurements[op.measure.name];
    read_profile(c.measurement, c);
    c.after = workspace;
    c.patch = std::move(sewn);
    c.run = std::move(run);
    c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    candidates.push_back(std::move(c));
    Candidate& added = candidates.back();
    Candidate* const previous_widest = widest;
    Candidate* const previous_best = best;
    if (widest == nullptr || added.width > widest->width) widest = &added;
    if (value(added) >= low_end && within_limits(added) && (best == nullptr || added.width < best->width))
      best = &added;
    for (Candidate* old : {previous_widest, previous_best})
      if (old != nullptr && old != widest && old != best) old->after = Workspace{};
    if (&added != widest && &added != best && !(value(added) >= low_end && value(added) <= high_end))
      added.after = Workspace{};
    return added;
  };

  std::string status, reason;
  const Candidate* chosen = nullptr;
  const Candidate& narrow = evaluate(op.width_min);
  if (value(narrow) >= low_end) {
    chosen = &narrow;
    status = within_limits(narrow) ? "met" : "infeasible";
    reason = "the narrowest patch of the range already gives " + quantity + " " + fixed(value(narrow), 3) +
             " >= " + fixed(low_end, 3) + (within_limits(narrow) ? "" : ", but beyond the bulge limit");
  } else {
    const Candidate& wide = evaluate(op.width_max);
    if (value(wide) < low_end) {
      chosen = &wide;
      status = "infeasible";
      reason = "the widest patch of the range gives only " + quantity + " " + fixed(value(wide), 3) +
               " < " + fixed(low_end, 3);
    } else {
      // False position between lo (below the band) and hi (at or above it).
      double lo_w = op.width_min, lo_g = value(narrow) - aim;
      double hi_w = op.width_max, hi_g = value(wide) - aim;
      int kept = 0;  // +1: hi kept in a row, -1: lo kept
      const Candidate* in_band = value(wide) <= high_end ? &wide : nullptr;
      while (in_band == nullptr && static_cast<int>(candidates.size()) < op.max_relaxations) {
        double w = lo_w - lo_g * (hi_w - lo_w) / (hi_g - lo_g);
        w = std::clamp(w, lo_w + 0.01 * (hi_w - lo_w), hi_w - 0.01 * (hi_w - lo_w));
        const Candidate& c = evaluate(w);
        const double g = value(c) - aim;
        if (value(c) >= low_end && value(c) <= high_end) in_band = &c;
        if (g < 0) {
          lo_w = w, lo_g = g;
          if (kept == 1) hi_g *= 0.5;
          kept = 1;
        } else {
          hi_w = w, hi_g = g;
          if (kept == -1) lo_g *= 0.5;
          kept = -1;
        }
      }
      if (in_band != nullptr) {
        chosen = in_band;
        status = within_limits(*in_band) ? "met" : "infeasible";
        reason = quantity + " " + fixed(value(*in_band), 3) + " is within [" + fixed(low_end, 3) + ", " +
                 fixed(high_end, 3) + "]" +
                 (within_limits(*in_band) ? "" : ", but the patch bulges beyond the limit: no width meets both");
      } else if (best != nullptr) {
        chosen = best;
        status = "not_within_tolerance";
        reason = "no candidate within [" + fixed(low_end, 3) + ", " + fixed(high_end, 3) + "] in " +
                 std::to_string(candidates.size()) +
                 " relaxations; the narrowest that meets the target within the limits is chosen";
      } else {
        chosen = widest;
        status = "infeasible";
        reason = "every candidate that meets the target bulges beyond the limit; the widest is left";
      }
    }
  }

  json list = json::array();
  for (const Candidate& c : candidates)
    list.push_back({{"width_mm", c.width},
                    {"min_area_mm2", c.min_area},
                    {"coarctation_index", c.coarctation_index},
                    {"bulge", c.bulge},
                    {"meets_target", value(c) >= low_end},
                    {"within_limits", within_limits(c)},
                    {"seconds", c.seconds}});
  json j = {{"object", op.patch.object},
            {"status", status},
            {"reason", reason},
            {"width_mm", chosen->width},
            {"target", {{"quantity", quantity}, {"value", op.target_value}, {"tolerance", op.tolerance}}},
            {"relaxations", candidates.size()},
            {"candidates", list},
            {"measurement", op.measure.name}};
  if (op.z_score)
    j["target"]["z_score"] = {{"z", op.z_score->z},
                              {"site", engine::arch_site_name(op.z_score->site)},
                              {"bsa_m2", op.z_score->bsa_m2},
                              {"diameter_mm", op.z_score->diameter_mm},
                              {"regression", "Pettersen et al., J Am Soc Echocardiogr 2008;21:922-934"}};
  if (op.max_bulge) j["max_bulge"] = *op.max_bulge;
  if (!op.plot.empty()) j["plot"] = op.plot.generic_string();
  std::string summary = status + ": width " + fixed(chosen->width, 2) + " mm, " + quantity + " " +
                        fixed(value(*chosen), 3) + " (" + reason + ")";
  if (op.z_score) {
    summary += "; target: ";
    summary += engine::arch_site_name(op.z_score->site);
    summary += " z " + fixed(op.z_score->z, 2) + " at BSA " + fixed(op.z_score->bsa_m2, 2) + " m^2, diameter " +
               fixed(op.z_score->diameter_mm, 2) + " mm";
  }
  j["summary"] = summary;
  // The chosen candidate's patch material and run, as its patch and simulate ops report them.
  if (chosen->patch.contains("material_index")) j["material_index"] = chosen->patch["material_index"];
  for (const char* key : {"s_reached", "residual", "equilibrium"})
    if (chosen->run.contains(key)) j[key] = chosen->run[key];
  if (chosen->run.contains("warning")) j["warning"] = "the chosen candidate: " + chosen->run["warning"].get<std::string>();

  if (!plot.empty()) {
    try {
      const std::vector<std::uint8_t> png = render::encode_png(render::draw_chart(design_chart(j)));
      engine::write_file_atomically(plot, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    } catch (...) {
      restore();
      throw;
    }
  }

  // The chosen candidate's workspace and measurement, as a plain replay of its three ops.
  workspace = chosen->after;
  measurements = measurements_before;
  measurements[op.measure.name] = chosen->measurement;
  undo_stack.resize(undo_depth);
  redo_stack.clear();
  return j;
}

}  // namespace sutura::app::detail
