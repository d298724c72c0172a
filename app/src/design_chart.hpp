#pragma once
// The plot of a design_patch result: one place for the op's `plot` PNG and the plan report's
// patch design section.
#include <nlohmann/json.hpp>

#include "sutura/render/chart.hpp"

namespace sutura::app {

/// From the op's result (report.json's details: `status`, `width_mm`, `target` {quantity,
/// value, tolerance}, `candidates` [{width_mm, min_area_mm2, coarctation_index, bulge}],
/// `max_bulge`): the quantity sized and the bulge against the width (candidates sorted by
/// width), the target band [value, value (1 + tolerance)], the bulge limit and the chosen
/// width. Throws std::invalid_argument for a result without candidates or with a field
/// missing. O(candidates log candidates).
render::Chart design_chart(const nlohmann::json& result);

}  // namespace sutura::app
