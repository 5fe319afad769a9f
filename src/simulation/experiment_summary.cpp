// The experiment's short summary: what compensation removed, per configuration, at the highest acceleration.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tuple>

#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::simulation {
namespace {

const RunResult* find(const std::vector<RunResult>& results, const std::string& robot, const std::string& motion,
                      double g, bool compensated, const std::string& variant) {
  for (const auto& r : results) {
    if (r.spec.robot == robot && r.spec.motion == motion && r.spec.acceleration_g == g &&
        r.spec.compensated == compensated && (!compensated || r.spec.variant == variant)) {
      return &r;
    }
  }
  return nullptr;
}

std::string removed(double without, double with) {
  if (std::abs(without) <= 0.0) return "–";
  return fmt::format("{:.0f} %", 100.0 * (1.0 - std::abs(with) / std::abs(without)));
}

}  // namespace

std::string experiment_summary(const std::vector<RunResult>& results) {
  double g = 0.0;
  for (const auto& r : results) g = std::max(g, r.spec.acceleration_g);
  std::string out = fmt::format(
      "At {:g} g, without → with compensation:\n\n"
      "| robot | motion | compensation | length error (mm) | removed | max deviation (mm) | removed | deviation area "
      "(mm²) | residual vibration (mm) |\n|---|---|---|---|---|---|---|---|---|\n",
      g);
  std::vector<std::tuple<std::string, std::string, std::string>> seen;
  for (const auto& r : results) {
    if (!r.spec.compensated) continue;
    const std::tuple<std::string, std::string, std::string> key{r.spec.robot, r.spec.motion, r.spec.variant};
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    const auto& [robot, motion, variant] = key;
    const RunResult* off = find(results, robot, motion, g, false, variant);
    const RunResult* on = find(results, robot, motion, g, true, variant);
    if (!off || !on) continue;
    const auto& a = off->metrics;
    const auto& b = on->metrics;
    out += fmt::format("| {} | {} | {} | {:.4f} → {:.4f} | {} | {:.4f} → {:.4f} | {} | {:.3f} → {:.3f} | {:.4f} → {:.4f} |\n",
                       robot, motion, variant, a.length_error_m * 1e3, b.length_error_m * 1e3,
                       removed(a.length_error_m, b.length_error_m), a.max_deviation_m * 1e3, b.max_deviation_m * 1e3,
                       removed(a.max_deviation_m, b.max_deviation_m), a.deviation_area_m2 * 1e6,
                       b.deviation_area_m2 * 1e6, a.residual_vibration_m * 1e3, b.residual_vibration_m * 1e3);
  }
  return out;
}

}  // namespace stiffpath::simulation
