#include "generate_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>

#include "sutura/engine/anatomy/segmentation_export.hpp"
#include "sutura/engine/atomic_file.hpp"
#include "sutura/engine/mesh_io.hpp"

namespace sutura::app {
namespace {

using engine::Vec3;

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

// Smallest interior angle over all faces, degrees.
double min_angle_deg(const engine::SurfaceMesh& mesh) {
  double lo = 180.0;
  for (const auto& f : mesh.faces())
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions()[f[k]];
      const Vec3 a = mesh.positions()[f[(k + 1) % 3]] - p;
      const Vec3 b = mesh.positions()[f[(k + 2) % 3]] - p;
      lo = std::min(lo, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi);
    }
  return lo;
}

nlohmann::json mesh_summary(const engine::SurfaceMesh& mesh, const std::string& file) {
  return {{"file", file},
          {"vertices", mesh.num_vertices()},
          {"faces", mesh.num_faces()},
          {"boundary_loops", mesh.boundary_loops().size()},
          {"mean_edge_length", mesh.mean_edge_length()},
          {"min_angle_deg", min_angle_deg(mesh)}};
}

nlohmann::json ends_json(const std::vector<engine::VesselEnd>& ends) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : ends)
    out.push_back({{"name", e.name}, {"centre", vec(e.centre)}, {"normal", vec(e.normal)},
                   {"radius", e.radius}});
  return out;
}

nlohmann::json params_json(const engine::ArchParams& p) {
  return {{"ascending_diameter", p.ascending_diameter},
          {"proximal_arch_diameter", p.proximal_arch_diameter},
          {"distal_arch_diameter", p.distal_arch_diameter},
          {"isthmus_diameter", p.isthmus_diameter},
          {"descending_diameter", p.descending_diameter},
          {"ascending_length", p.ascending_length},
          {"arch_radius", p.arch_radius},
          {"arch_tilt_deg", p.arch_tilt_deg},
          {"descending_length", p.descending_length},
          {"coarctation_fraction", p.coarctation_fraction},
          {"coarctation_offset", p.coarctation_offset},
          {"coarctation_length", p.coarctation_length},
          {"innominate_angle_deg", p.innominate_angle_deg},
          {"carotid_angle_deg", p.carotid_angle_deg},
          {"subclavian_angle_deg", p.subclavian_angle_deg},
          {"lsa_diameter", p.lsa_diameter},
          {"lsa_length", p.lsa_length},
          {"head_neck_branches", p.head_neck_branches},
          {"innominate_diameter", p.innominate_diameter},
          {"innominate_length", p.innominate_length},
          {"carotid_diameter", p.carotid_diameter},
          {"carotid_length", p.carotid_length},
          {"pulmonary_trunk_diameter", p.pulmonary_trunk_diameter},
          {"pulmonary_branch_diameter", p.pulmonary_branch_diameter},
          {"pulmonary_branch_length", p.pulmonary_branch_length},
          {"pulmonary_gap", p.pulmonary_gap},
          {"junction_blend", p.junction_blend},
          {"target_edge_length", p.target_edge_length}};
}

}  // namespace

CLI::App* add_generate_command(CLI::App& app, GenerateArchOptions& o) {
  auto* generate = app.add_subcommand("generate", "Generate synthetic anatomy");
  generate->require_subcommand(1);
  auto* arch = generate->add_subcommand(
      "arch", "Infant aortic arch with coarctation, arch branches and pulmonary artery: writes "
              "aorta.ply, pulmonary.ply and landmarks.json into --out");
  arch->add_option("-o,--out", o.out_dir, "Output directory (created if missing)")->required();
  arch->add_option("--resolution", o.resolution,
                   "coarse (edge 1.1 mm, ~4k aorta faces) or fine (0.52 mm, ~20k)")
      ->capture_default_str()
      ->check(CLI::IsMember({"coarse", "fine"}));
  arch->add_option("--edge-length", o.edge_length,
                   "Target edge length in mm (0.2 ... 2); overrides --resolution");
  arch->add_option("--coarctation", o.coarctation,
                   "Narrowest lumen diameter as a fraction of the descending aorta (0.2 ... 1)");
  arch->add_option("--lsa-length", o.lsa_length,
                   "Left subclavian length in mm from the aortic centreline to its open end "
                   "(default 14; a subclavian flap needs about the aortotomy's length)");
  arch->add_option("--branches", o.branches,
                   "all: innominate, left common carotid and left subclavian; lsa: subclavian only")
      ->capture_default_str()
      ->check(CLI::IsMember({"all", "lsa"}));
  arch->add_flag("--as-segmentation", o.as_segmentation,
                 "Also write aorta_segmentation.stl: the aorta as a segmentation tool exports it "
                 "(closed by flat caps, dense, noisy, unwelded binary STL), the input of `prepare`");
  arch->add_option("--segmentation-edge", o.segmentation_edge,
                   "Largest mean edge of the segmentation export, mm (faces are split into four "
                   "until it holds)")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 2.0));
  arch->add_option("--segmentation-noise", o.segmentation_noise,
                   "Noise of the segmentation export along the normals, mm (uniform, +-; default: "
                   "7 % of --segmentation-edge)")
      ->check(CLI::Range(0.0, 0.5));
  arch->add_flag("-q,--quiet", o.quiet, "No summary on stderr");
  return arch;
}

engine::ArchParams arch_params(const GenerateArchOptions& o) {
  engine::ArchParams p;
  p.target_edge_length = o.edge_length.value_or(
      o.resolution == "fine" ? engine::kArchFineEdgeLength : engine::kArchCoarseEdgeLength);
  if (o.coarctation) p.coarctation_fraction = *o.coarctation;
  if (o.lsa_length) p.lsa_length = *o.lsa_length;
  p.head_neck_branches = o.branches == "all";
  return p;
}

nlohmann::json landmarks_json(const engine::ArchAnatomy& a, const engine::ArchParams& params) {
  const engine::ArchLandmarks& l = a.landmarks;
  nlohmann::json centrelines = nlohmann::json::array();
  for (const auto& c : l.centrelines) {
    nlohmann::json points = nlohmann::json::array();
    for (const Vec3& p : c.points) points.push_back(vec(p));
    centrelines.push_back({{"name", c.name}, {"points", points}, {"radii", c.radii}});
  }
  return {
      {"format", "sutura-anatomy-landmarks"},
      {"version", 1},
      {"units", "mm"},
      {"frame", "x patient left, y posterior, z superior; origin at the aortic root end centre"},
      {"params", params_json(params)},
      {"aorta", {{"mesh", mesh_summary(a.aorta, "aorta.ply")}, {"ends", ends_json(l.aorta_ends)}}},
      {"pulmonary",
       {{"mesh", mesh_summary(a.pulmonary, "pulmonary.ply")}, {"ends", ends_json(l.pulmonary_ends)}}},
      {"coarctation",
       {{"centre", vec(l.coarctation_centre)},
        {"axis", vec(l.coarctation_axis)},
        {"min_radius", l.coarctation_min_radius},
        {"length", l.coarctation_length}}},
      {"left_subclavian",
       {{"origin", vec(l.lsa_origin)},
        {"axis", vec(l.lsa_axis)},
        {"tip", vec(l.lsa_tip)},
        {"radius", l.lsa_radius}}},
      {"centrelines", centrelines}};
}

int run_generate_arch(const GenerateArchOptions& o) {
  const engine::ArchParams params = arch_params(o);
  const auto start = std::chrono::steady_clock::now();
  const engine::ArchAnatomy anatomy = engine::generate_arch(params);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::filesystem::path dir(o.out_dir);
  std::filesystem::create_directories(dir);
  engine::save_mesh(anatomy.aorta, dir / "aorta.ply");
  engine::save_mesh(anatomy.pulmonary, dir / "pulmonary.ply");
  engine::write_file_atomically(dir / "landmarks.json", landmarks_json(anatomy, params).dump(2) + "\n");
  if (o.as_segmentation) {
    engine::SegmentationLikeParams sp;
    sp.max_edge_length = o.segmentation_edge;
    sp.noise = o.segmentation_noise.value_or(0.07 * o.segmentation_edge);
    // From the fine surface at the coarsest: a segmentation resolves curvature well below a
    // millimetre, and the coarse arch's facets would be creases in it.
    const engine::SurfaceMesh export_mesh = engine::segmentation_like(
        params.target_edge_length > engine::kArchFineEdgeLength
            ? engine::generate_arch([&] {
                engine::ArchParams fine = params;
                fine.target_edge_length = engine::kArchFineEdgeLength;
                return fine;
              }()).aorta
            : anatomy.aorta,
        sp);
    engine::save_mesh(export_mesh, dir / "aorta_segmentation.stl");
    if (!o.quiet)
      std::cerr << "sutura: aorta_segmentation.stl: " << export_mesh.num_faces()
                << " faces, closed, mean edge " << export_mesh.mean_edge_length() << " mm\n";
  }
  if (!o.quiet) {
    for (const auto* m : {&anatomy.aorta, &anatomy.pulmonary})
      std::cerr << "sutura: " << (m == &anatomy.aorta ? "aorta" : "pulmonary") << ": "
                << m->num_vertices() << " vertices, " << m->num_faces() << " faces, "
                << m->boundary_loops().size() << " open ends, min angle " << min_angle_deg(*m)
                << " deg\n";
    std::cerr << "sutura: generated in " << seconds << " s into " << dir.string() << "/\n";
  }
  return 0;
}

}  // namespace sutura::app
