#include "design_chart.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace sutura::app {

render::Chart design_chart(const nlohmann::json& result) {
  try {
    const nlohmann::json& target = result.at("target");
    const bool area = target.at("quantity").get<std::string>() == "min_area_mm2";
    const double low = target.at("value").get<double>();
    const double high = low * (1.0 + target.at("tolerance").get<double>());
    const nlohmann::json& candidates = result.at("candidates");
    if (!candidates.is_array() || candidates.empty())
      throw std::invalid_argument("design chart: the result has no candidates");
    std::vector<std::array<double, 3>> rows;  // width, quantity, bulge
    for (const nlohmann::json& c : candidates)
      rows.push_back({c.at("width_mm").get<double>(),
                      c.at(area ? "min_area_mm2" : "coarctation_index").get<double>(), c.at("bulge").get<double>()});
    std::sort(rows.begin(), rows.end());
    render::Chart chart;
    chart.title = std::string(area ? "Smallest lumen area" : "Coarctation index") +
                  " and bulge against the width: " + result.at("status").get<std::string>();
    chart.x_label = "patch width [mm]";
    chart.y_label = area ? "smallest lumen area [mm2]" : "coarctation index";
    chart.y2_label = "bulge (widest / distal diameter)";
    render::ChartSeries quantity, bulge;
    quantity.label = area ? "smallest lumen area" : "coarctation index";
    bulge.label = "bulge";
    bulge.color = {214, 39, 40, 255};
    bulge.right_axis = true;
    for (const auto& [w, q, b] : rows) {
      quantity.points.push_back({w, q});
      bulge.points.push_back({w, b});
    }
    chart.series = {quantity, bulge};
    chart.bands.push_back({low, high, false, {200, 232, 200, 255}});
    if (result.contains("max_bulge")) {
      const double limit = result["max_bulge"].get<double>();
      chart.bands.push_back({limit, limit, true, {214, 39, 40, 255}});
    }
    const double chosen = result.at("width_mm").get<double>();
    char label[64];
    std::snprintf(label, sizeof label, "chosen %.2f mm", chosen);
    chart.markers.push_back({chosen, label});
    return chart;
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(std::string("design chart: the result lacks a field: ") + e.what());
  }
}

}  // namespace sutura::app
