// The scan result as JSON: the shared path metrics plus the scan's own figures and warnings, units in the keys.
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
  return out;
}

}  // namespace stiffpath::vision
