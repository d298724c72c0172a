#include "prepare_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "sutura/app/report.hpp"
#include "sutura/engine/atomic_file.hpp"
#include "sutura/engine/mesh_io.hpp"

namespace sutura::app {
namespace {

nlohmann::json vec(const engine::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// One --clip value, "ox,oy,oz,nx,ny,nz[,radius]": six or seven finite numbers, no empty field.
// Throws CLI::ValidationError naming the value and what is wrong with it.
engine::PrepareClip parse_clip(const std::string& v) {
  const auto fail = [&](const std::string& why) { throw CLI::ValidationError("--clip", "'" + v + "': " + why); };
  if (v.empty() || v.back() == ',') fail("give ox,oy,oz,nx,ny,nz or ox,oy,oz,nx,ny,nz,radius");
  std::vector<double> x;
  std::istringstream in(v);
  for (std::string part; std::getline(in, part, ',');) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || !std::isfinite(value)) fail("'" + part + "' is not a finite number");
    x.push_back(value);
  }
  if (x.size() != 6 && x.size() != 7) fail("give ox,oy,oz,nx,ny,nz or ox,oy,oz,nx,ny,nz,radius");
  engine::PrepareClip clip;
  clip.origin = {x[0], x[1], x[2]};
  clip.normal = {x[3], x[4], x[5]};
  if (x.size() == 7) clip.radius = x[6];
  return clip;
}

// centreline.json: the tree as extract_centreline gives it (points and radii in mm, edges as
// point index pairs, each end's point by name).
nlohmann::json centreline_json(const engine::CentrelineTree& t, const engine::PrepareResult& r) {
  nlohmann::json points = nlohmann::json::array(), edges = nlohmann::json::array(), ends = nlohmann::json::array();
  for (const auto& p : t.points) points.push_back(vec(p));
  for (const auto& [a, b] : t.edges) edges.push_back({a, b});
  for (std::size_t e = 0; e < t.end_nodes.size(); ++e) ends.push_back({{"name", r.ends[e].end.name}, {"point", t.end_nodes[e]}});
  return {{"format", "sutura-centreline"}, {"version", 1},        {"units", "mm"},
          {"points", points},              {"radii", t.radii},    {"edges", edges},
          {"branch_points", t.branch_points}, {"ends", ends}};
}

}  // namespace

CLI::App* add_prepare_command(CLI::App& app, PrepareOptions& o) {
  auto* prepare = app.add_subcommand(
      "prepare", "Turn a segmentation export (closed, dense STL/OBJ/PLY with flat end caps) into a "
                 "vessel to plan on: opens the caps, smooths, remeshes; writes vessel.ply, "
                 "centreline.json (not with --keep-caps) and prepare.json into --out");
  prepare->add_option("input", o.input, "Mesh file from the segmentation tool")->required();
  prepare->add_option("-o,--out", o.out_dir, "Output directory (created if missing)")->required();
  prepare->add_option("--edge-length", o.params.edge_length,
                      "Target edge length in mm (default: 16 edges around the narrowest end; "
                      "allowed: from 64 to 6 edges around it)");
  prepare->add_option("--clip", o.clips,
                      "Clip an end at a plane: ox,oy,oz,nx,ny,nz[,radius] (mm; the normal points to "
                      "the part removed; edges within radius of the origin are cut, default 10); repeatable")
      ->each([](const std::string& v) { (void)parse_clip(v); });
  prepare->add_flag("--keep-caps", o.params.keep_caps,
                    "Find the flat end caps and report them, but keep them closed");
  prepare->add_option("--smoothing", o.params.smoothing_iterations,
                      "Taubin smoothing iterations against segmentation noise (0: none)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  prepare->add_option("--max-faces", o.params.max_faces, "Most faces of the result")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t(1), std::size_t(20'000'000)));
  prepare->add_option("--max-input-faces", o.max_input_faces,
                      "Most triangles of the input file (refused before it is read)")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t(1), engine::kMaxPrepareInputFaces));
  prepare->add_flag("-q,--quiet", o.quiet, "No summary on stderr");
  return prepare;
}

nlohmann::json prepare_json(const engine::PrepareResult& r, const PrepareOptions& o, double seconds,
                            const std::optional<engine::CentrelineTree>& centreline, double centreline_seconds) {
  nlohmann::json ends = nlohmann::json::array();
  for (const auto& e : r.ends)
    ends.push_back({{"name", e.end.name},
                    {"centre", vec(e.end.centre)},
                    {"normal", vec(e.end.normal)},
                    {"radius", e.end.radius},
                    {"flatness", e.flatness},
                    {"from", e.was_cap ? (o.params.keep_caps ? "cap (kept)" : "cap (opened)") : "open end"},
                    {"cap_faces", e.cap_faces}});
  nlohmann::json steps = nlohmann::json::object();
  for (const auto& [step, t] : r.step_seconds) steps[step] = t;
  nlohmann::json clips = nlohmann::json::array();
  for (std::size_t k = 0; k < r.clipped.size(); ++k) {
    const engine::PrepareClip& c = o.params.clips[k];
    clips.push_back({{"origin", vec(c.origin)}, {"normal", vec(c.normal)}, {"radius", c.radius},
                     {"removed_faces", r.clipped[k].first}, {"removed_area", r.clipped[k].second}});
  }
  nlohmann::json dropped = nlohmann::json::array();
  for (const auto& d : r.dropped)
    dropped.push_back({{"faces", d.faces}, {"area", d.area}, {"centroid", vec(d.centroid)}});
  return {{"format", "sutura-prepare-report"},
          {"version", 1},
          {"units", "mm"},
          {"input", {{"file", o.input}, {"vertices", r.input_vertices}, {"faces", r.input_faces}}},
          {"output",
           {{"file", "vessel.ply"},
            {"vertices", r.vessel.num_vertices()},
            {"faces", r.vessel.num_faces()},
            {"boundary_loops", r.vessel.boundary_loops().size()}}},
          {"clips", clips},
          {"dropped_components", dropped},
          {"flipped_orientation", r.flipped},
          {"ends", ends},
          {"edge_length", {{"target", r.edge_length},
                           {"derived", r.edge_length_derived},
                           {"min", r.min_edge},
                           {"max", r.max_edge},
                           {"mean", r.mean_edge}}},
          {"min_angle_deg", r.min_angle_deg},
          {"smoothing_iterations", o.params.smoothing_iterations},
          {"hausdorff_to_input", hausdorff_json(r.to_input)},
          {"hausdorff_spacing_mm", r.hausdorff_spacing},
          {"centreline", centreline ? nlohmann::json{{"file", "centreline.json"},
                                                     {"points", centreline->points.size()},
                                                     {"branch_points", centreline->branch_points.size()},
                                                     {"seconds", centreline_seconds}}
                                    : nlohmann::json(nullptr)},
          {"seconds", seconds},
          {"step_seconds", steps}};
}

int run_prepare(const PrepareOptions& o) {
  namespace fs = std::filesystem;
  const fs::path dir(o.out_dir);
  const fs::path vessel_file = dir / "vessel.ply", report_file = dir / "prepare.json",
                 centreline_file = dir / "centreline.json";
  std::error_code ec;
  for (const auto& out : {vessel_file, report_file, centreline_file})
    if (fs::exists(out, ec) && fs::equivalent(out, o.input, ec))
      throw engine::InvalidArgument("prepare: " + out.string() +
                                    " is the input file; choose another --out directory");
  // The --clip strings (checked when the command line was parsed) become the parameters' clips.
  PrepareOptions options = o;
  engine::PrepareParams& params = options.params;
  for (const std::string& v : o.clips) params.clips.push_back(parse_clip(v));
  const auto start = std::chrono::steady_clock::now();
  engine::ImportOptions io;
  io.max_faces = o.max_input_faces;
  const engine::SurfaceMesh input = engine::load_mesh(o.input, io);
  const engine::PrepareResult result = engine::prepare_vessel(input, params);
  // The automatic centreline runs between open ends: none with --keep-caps or a single end.
  std::optional<engine::CentrelineTree> centreline;
  const auto centreline_start = std::chrono::steady_clock::now();
  if (!o.params.keep_caps && result.ends.size() >= 2) {
    std::vector<engine::VesselEnd> ends;
    for (const auto& e : result.ends) ends.push_back(e.end);
    centreline = engine::extract_centreline(result.vessel, ends);
  }
  const auto end = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(end - start).count();
  const double centreline_seconds = std::chrono::duration<double>(end - centreline_start).count();
  fs::create_directories(dir);
  // An earlier report goes first, so that a failure leaves no report beside a vessel it does
  // not describe; an earlier centreline too.
  fs::remove(report_file);
  fs::remove(centreline_file);
  engine::save_mesh(result.vessel, vessel_file);
  if (centreline) engine::write_file_atomically(centreline_file, centreline_json(*centreline, result).dump(1) + "\n");
  engine::write_file_atomically(report_file,
                                prepare_json(result, options, seconds, centreline, centreline_seconds).dump(2) + "\n");
  if (!o.quiet) {
    std::cerr << "sutura: " << o.input << ": " << result.input_faces << " faces in, "
              << result.vessel.num_faces() << " out (edge " << result.edge_length << " mm, min angle "
              << result.min_angle_deg << " deg, Hausdorff to the input " << result.to_input.a_to_b
              << " mm)\n";
    for (const auto& d : result.dropped)
      std::cerr << "sutura: dropped a component of " << d.faces << " faces (" << d.area << " mm^2)\n";
    for (const auto& e : result.ends)
      std::cerr << "sutura: " << e.end.name << ": radius " << e.end.radius << " mm at ("
                << e.end.centre.x() << ", " << e.end.centre.y() << ", " << e.end.centre.z() << ")"
                << (e.was_cap ? (o.params.keep_caps ? ", cap kept" : ", cap opened") : ", open end") << "\n";
    std::cerr << "sutura: prepared in " << seconds << " s into " << dir.string() << "/\n";
  }
  return 0;
}

}  // namespace sutura::app
