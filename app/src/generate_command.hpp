#pragma once
// `sutura generate arch`: writes the synthetic infant aortic arch (aorta.ply, pulmonary.ply)
// and its landmarks (landmarks.json) into a directory, and on request a synthetic segmentation
// export of the aorta (aorta_segmentation.stl). See docs/anatomy.md and docs/patient-data.md.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "sutura/engine/anatomy/aortic_arch.hpp"

namespace sutura::app {

struct GenerateArchOptions {
  std::string out_dir;
  std::string resolution = "coarse";   ///< "coarse" | "fine": kArchCoarse/FineEdgeLength
  std::optional<double> edge_length;   ///< mm; overrides the resolution
  std::optional<double> coarctation;   ///< ArchParams::coarctation_fraction
  std::optional<double> lsa_length;    ///< mm, ArchParams::lsa_length
  std::string branches = "all";        ///< "all" (innominate, carotid, subclavian) | "lsa"
  /// Also write aorta_segmentation.stl: the aorta (generated at the fine resolution at the
  /// coarsest) closed by flat caps, subdivided to segmentation_edge and noisy
  /// (engine::segmentation_like), as an unwelded binary STL.
  bool as_segmentation = false;
  double segmentation_edge = 0.3;  ///< mm
  /// mm; default 7 % of segmentation_edge (a segmentation's noise scales with its voxels,
  /// and so does its triangle size)
  std::optional<double> segmentation_noise;
  bool quiet = false;
};

/// Adds `generate` with its `arch` subcommand to `app`; returns the `arch` subcommand, which is
/// parsed when it is given on the command line.
CLI::App* add_generate_command(CLI::App& app, GenerateArchOptions& options);

/// The model parameters the options select (defaults otherwise).
engine::ArchParams arch_params(const GenerateArchOptions& options);

/// landmarks.json content: format header, the parameters, per-object mesh summary, landmarks.
nlohmann::json landmarks_json(const engine::ArchAnatomy& anatomy, const engine::ArchParams& params);

/// Generates and writes the files (each atomically). Throws engine::InvalidArgument for bad
/// parameters and engine::MeshIoError / std::runtime_error when writing fails. Returns 0.
int run_generate_arch(const GenerateArchOptions& options);

}  // namespace sutura::app
