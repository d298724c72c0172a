#pragma once
// `sutura prepare INPUT --out DIR`: a segmentation export (closed, dense, noisy STL with flat
// end caps) becomes a vessel to plan on: DIR/vessel.ply, DIR/centreline.json (the automatic
// centreline; not with --keep-caps or for a vessel of one end: it runs between open ends) and
// DIR/prepare.json. The steps and their limits: engine/include/sutura/engine/patient/
// prepare.hpp, engine/include/sutura/engine/measure/centreline.hpp, docs/patient-data.md.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "sutura/engine/measure/centreline.hpp"
#include "sutura/engine/patient/prepare.hpp"

namespace sutura::app {

struct PrepareOptions {
  std::string input;
  std::string out_dir;
  engine::PrepareParams params;
  /// --clip values as given: "ox,oy,oz,nx,ny,nz[,radius]" each (parsed into params.clips).
  std::vector<std::string> clips;
  std::size_t max_input_faces = 4'000'000;  ///< refused before parsing beyond this (at most
                                            ///< engine::kMaxPrepareInputFaces)
  bool quiet = false;
};

/// Adds the `prepare` subcommand to `app` and returns it.
CLI::App* add_prepare_command(CLI::App& app, PrepareOptions& options);

/// prepare.json content: format header, input and result counts, the ends, the dropped
/// components, quality, the Hausdorff distance to the input and the centreline's summary
/// (null when none was extracted).
nlohmann::json prepare_json(const engine::PrepareResult& result, const PrepareOptions& options,
                            double seconds, const std::optional<engine::CentrelineTree>& centreline,
                            double centreline_seconds);

/// Loads, prepares and writes (each file atomically; the input is never overwritten). Throws
/// engine::MeshIoError, engine::PrepareError or engine::InvalidArgument with a message that
/// names the file or the problem. Returns 0.
int run_prepare(const PrepareOptions& options);

}  // namespace sutura::app
