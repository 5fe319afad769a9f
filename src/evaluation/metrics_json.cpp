// Path metrics as JSON with units in the keys, SI converted to mm / mm² / degrees at this edge.
#include "stiffpath/evaluation/metrics_json.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "stiffpath/core/units.hpp"

namespace stiffpath::evaluation {

double round_for_json(double value) {
  if (!std::isfinite(value)) return 0.0;
  if (value == 0.0) return 0.0;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return std::strtod(buffer, nullptr);
}

namespace {
double mm(double m) { return round_for_json(units::m_to_mm(m)); }
double mm2(double m2) { return round_for_json(m2 * 1e6); }
nlohmann::json point_mm(const Point2& p) { return nlohmann::json::array({mm(p.x()), mm(p.y())}); }
}  // namespace

nlohmann::json to_json(const SideMetrics& side) {
  const Point2& d = side.fit.line.direction;
  return {{"length_mm", mm(side.length_m)},
          {"deviation_area_mm2", mm2(side.deviation_area_m2)},
          {"max_deviation_mm", mm(side.max_deviation_m)},
          {"straightness_mm", mm(side.straightness_m)},
          {"direction_deg", round_for_json(units::rad_to_deg(std::atan2(d.y(), d.x())))},
          {"start_mm", point_mm(side.start)},
          {"end_mm", point_mm(side.end)},
          {"rms_residual_mm", mm(side.fit.rms_residual_m)},
          {"points", side.point_count}};
}

nlohmann::json to_json(const PathMetrics& metrics) {
  nlohmann::json out = {{"length_mm", mm(metrics.length_m)},
                        {"deviation_area_mm2", mm2(metrics.deviation_area_m2)},
                        {"max_deviation_mm", mm(metrics.max_deviation_m)},
                        {"straightness_mm", mm(metrics.straightness_m)},
                        {"closed", metrics.closed}};
  if (metrics.sides.size() > 1) {
    nlohmann::json sides = nlohmann::json::array();
    for (const auto& side : metrics.sides) sides.push_back(to_json(side));
    out["sides"] = std::move(sides);
  }
  if (!metrics.corners.empty()) {
    nlohmann::json corners = nlohmann::json::array();
    for (const auto& c : metrics.corners) {
      nlohmann::json corner = {{"x_mm", mm(c.position.x())},
                               {"y_mm", mm(c.position.y())},
                               {"angle_deg", round_for_json(units::rad_to_deg(c.angle_rad))}};
      if (c.path_distance_m) corner["path_distance_mm"] = mm(*c.path_distance_m);
      corners.push_back(std::move(corner));
    }
    out["corners"] = std::move(corners);
  }
  return out;
}

}  // namespace stiffpath::evaluation
