// The scan result as JSON: the shared path metrics plus the scan's own figures and warnings, units in the keys.
#include <cmath>

#include "stiffpath/core/units.hpp"
#include "stiffpath/evaluation/metrics_json.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {

nlohmann::json to_json(const ScanResult& r) {
  using evaluation::round_for_json;
  nlohmann::json out = evaluation::to_json(r.metrics);
  out["width_mm"] = round_for_json(units::m_to_mm(r.width_m));
  out["length_uncertainty_mm"] = round_for_json(units::m_to_mm(r.length_uncertainty_m));
  if (out.contains("sides")) {
    for (std::size_t k = 0; k < r.sides.size(); ++k) {
      out["sides"][k]["width_mm"] = round_for_json(units::m_to_mm(r.sides[k].width_m));
      out["sides"][k]["rejected_sections"] = r.sides[k].rejected_sections;
    }
  }
  std::size_t rejected = 0, sections = 0;
  for (const auto& s : r.sides) rejected += s.rejected_sections, sections += s.sections;
  out["dpi"] = round_for_json(r.dpi);
  out["image_px"] = {r.width_px, r.height_px};
  out["mark_darkness"] = round_for_json(r.mark_darkness);
  out["paper_noise"] = round_for_json(r.paper_noise);
  out["cross_sections"] = sections;
  out["rejected_sections"] = rejected;
  out["specks_ignored"] = r.specks_ignored;
  out["warnings"] = r.warnings;
  out["centre_line"] = centre_line_json(r);
  return out;
}

nlohmann::json centre_line_json(const ScanResult& r) {
  const auto tenth_um = [](double m) { return std::round(units::m_to_mm(m) * 1e4) / 1e4; };  // mm, to 0.1 µm
  nlohmann::json sides = nlohmann::json::array();
  for (const auto& side : r.sides) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : side.centres) points.push_back({tenth_um(p.x()), tenth_um(p.y())});
    sides.push_back(std::move(points));
  }
  return {{"frame", kCentreLineFrame}, {"sides_mm", std::move(sides)}};
}

}  // namespace stiffpath::vision
