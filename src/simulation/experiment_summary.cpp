// The experiment's summary: what compensation removed, per configuration, one table per acceleration.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <tuple>

#include "stiffpath/core/units.hpp"
#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::simulation {
namespace {

const RunResult* find(const std::vector<RunResult>& results, const std::string& robot, const std::string& motion,
                      double a, CompensationVariant variant) {
  for (const auto& r : results) {
    if (r.spec.robot == robot && r.spec.motion == motion && r.spec.acceleration_m_s2 == a && r.spec.variant == variant) {
      return &r;
    }
  }
  return nullptr;
}

std::string removed(double without, double with) {
  if (std::abs(without) <= 0.0) return "–";
  return fmt::format("{:.0f} %", 100.0 * (1.0 - std::abs(with) / std::abs(without)));
}

std::string summary_at(const std::vector<RunResult>& results, double a) {
  std::string out = fmt::format(
      "At {:g} g, without → with compensation:\n\n"
      "| robot | motion | compensation | length error (mm) | removed | max deviation (mm) | removed | deviation area "
      "(mm²) | residual vibration (mm) |\n|---|---|---|---|---|---|---|---|---|\n",
      a / units::standard_gravity_m_s2);
  std::vector<std::tuple<std::string, std::string, CompensationVariant>> seen;
  for (const auto& r : results) {
    if (!r.spec.compensated()) continue;
    const std::tuple<std::string, std::string, CompensationVariant> key{r.spec.robot, r.spec.motion, r.spec.variant};
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) continue;
    seen.push_back(key);
    const auto& [robot, motion, variant] = key;
    const RunResult* off = find(results, robot, motion, a, CompensationVariant::without);
    const RunResult* on = find(results, robot, motion, a, variant);
    if (!off || !on) continue;
    const auto& before = off->metrics;
    const auto& after = on->metrics;
    out += fmt::format("| {} | {} | {} | {:.4f} → {:.4f} | {} | {:.4f} → {:.4f} | {} | {:.3f} → {:.3f} | {:.4f} → {:.4f} |\n",
                       robot, motion, core::enum_name(variant), before.length_error_m * 1e3, after.length_error_m * 1e3,
                       removed(before.length_error_m, after.length_error_m), before.max_deviation_m * 1e3,
                       after.max_deviation_m * 1e3, removed(before.max_deviation_m, after.max_deviation_m),
                       before.deviation_area_m2 * 1e6, after.deviation_area_m2 * 1e6,
                       before.residual_vibration_m * 1e3, after.residual_vibration_m * 1e3);
  }
  return out;
}

}  // namespace

std::string experiment_summary(const std::vector<RunResult>& results) {
  std::vector<double> levels;
  for (const auto& r : results) levels.push_back(r.spec.acceleration_m_s2);
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  // What each compensation is, as every surface defines it (job::JobSpec), so that no filter goes unnamed.
  std::string out =
      "Compensations: without = the planned path converted to joints as it is (no reference filter); thesis = the "
      "thesis's method (bilinear model, quasi-static, no filter; `run --thesis`); default = what `run` does by "
      "default (the model cross-validation favours, dynamic compensation, 8 ms smoothing).\n";
  for (const double a : levels) out += "\n" + summary_at(results, a);
  return out;
}

}  // namespace stiffpath::simulation
