// The robustness sweep: damping, mass, servo bandwidth and campaign noise off nominal, over truth/campaign seeds.
#include "stiffpath/simulation/robustness.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <map>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::simulation {
namespace {

struct Condition {
  std::string factor;
  double value = 0.0;
};

// The nominal tip damping ratio: the one set, else the robot file's.
double nominal_damping_ratio(const RobustnessOptions& o, const kinematics::Robot& robot) {
  return o.base.simulation.plant.tip_damping_ratio.value_or(robot.tip_damping_ratio);
}

std::vector<Condition> conditions(const RobustnessOptions& o, double zeta0) {
  std::vector<Condition> c{{"nominal", 0.0}};
  for (double z : o.damping_ratios) {
    if (z != zeta0) c.push_back({"damping_ratio", z});
  }
  for (double e : o.mass_errors) {
    if (e != 0.0) c.push_back({"mass_error", e});
  }
  for (double f : o.servo_bandwidths_hz) {
    if (f != o.base.simulation.plant.servo_bandwidth_hz) c.push_back({"servo_bandwidth_hz", f});
  }
  for (double s : o.noise_sigmas_m) {
    if (s != o.base.fit.noise_sigma_m) c.push_back({"noise_um", s * 1e6});  // the table's factor, in µm
  }
  return c;
}

void check(const RobustnessOptions& o) {
  if (o.seeds < 1 || o.seeds > 100) throw Error(fmt::format("robustness: seeds {} outside 1 … 100", o.seeds));
  if (o.motions.empty() || o.variants.empty()) throw Error("robustness: no motions or no variants");
  for (double z : o.damping_ratios) {
    if (!(z >= 0.0 && z <= 2.0)) throw Error(fmt::format("robustness: damping ratio {} outside [0, 2]", z));
  }
  for (double e : o.mass_errors) {
    if (!(e > -0.9 && e < 9.0)) throw Error(fmt::format("robustness: mass error {} outside (−0.9, 9)", e));
  }
  for (double f : o.servo_bandwidths_hz) {
    if (!(f > 0.0 && f <= 2000.0)) throw Error(fmt::format("robustness: servo bandwidth {} Hz outside (0, 2000]", f));
  }
  for (double s : o.noise_sigmas_m) {
    if (!(s >= 0.0 && s <= 1e-3)) throw Error(fmt::format("robustness: noise {} µm outside [0, 1000]", s * 1e6));
  }
  const int runs = robustness_run_count(o);
  if (runs > o.max_runs) {
    throw Error(fmt::format("robustness: {} runs asked for, more than the limit of {} (fewer seeds or values)", runs,
                            o.max_runs));
  }
}

// A reported statistic of the runs: the textbook median, the mean of the two middle values of an even count.
double median(std::vector<double> v) { return core::median(std::move(v), core::MedianRule::mean_of_middles); }

}  // namespace

int robustness_run_count(const RobustnessOptions& o) {
  const double zeta0 = nominal_damping_ratio(o, kinematics::load_robot(o.robot));
  return static_cast<int>(conditions(o, zeta0).size() * o.variants.size() * o.motions.size()) * o.seeds;
}

std::vector<RobustnessRow> run_robustness(const RobustnessOptions& options) {
  check(options);
  const kinematics::Robot robot = kinematics::load_robot(options.robot);
  const double zeta0 = nominal_damping_ratio(options, robot);
  ExperimentOptions base = options.base;
  base.motions = {"x", "y", "triangle"};
  base.paths.clear();
  base.variants.clear();
  for (const auto v : options.variants) {
    if (v != CompensationVariant::without) base.variants.push_back(v);
  }
  base.truth.base = make_true_base(robot, base.truth);  // one structural fit, perturbed per seed
  std::vector<RobustnessRow> rows;
  std::map<std::string, std::vector<double>> atp;  // per row: AT_p of each seed
  for (const auto& c : conditions(options, zeta0)) {
    for (const auto& variant : options.variants) {
      for (const auto& motion : options.motions) rows.push_back({c.factor, c.value, variant, motion});
    }
  }
  const auto row_of = [&](const Condition& c, CompensationVariant variant, const std::string& motion) -> RobustnessRow& {
    for (auto& r : rows) {
      if (r.factor == c.factor && r.value == c.value && r.variant == variant && r.motion == motion) return r;
    }
    throw Error("robustness: internal row lookup failed");
  };
  for (int seed = 1; seed <= options.seeds; ++seed) {
    // The models depend on the seed and the campaign noise only.
    std::map<double, TwinModels> models;
    for (const auto& c : conditions(options, zeta0)) {
      ExperimentOptions o = base;
      o.truth.seed = static_cast<std::uint64_t>(seed);
      o.fit.seed = 1000 + static_cast<std::uint64_t>(seed);
      if (c.factor == "noise_um") o.fit.noise_sigma_m = c.value * 1e-6;
      if (c.factor == "damping_ratio") o.simulation.plant.tip_damping_ratio = c.value;
      if (c.factor == "mass_error") o.simulation.mass_scale = 1.0 + c.value;
      if (c.factor == "servo_bandwidth_hz") o.simulation.plant.servo_bandwidth_hz = c.value;
      if (!models.count(o.fit.noise_sigma_m)) models.emplace(o.fit.noise_sigma_m, make_twin_models(robot, o));
      const TwinModels& twin = models.at(o.fit.noise_sigma_m);
      for (const auto& variant : options.variants) {
        for (const auto& motion : options.motions) {
          const RunResult r = run_once({robot.name, motion, options.acceleration_m_s2, variant}, robot, twin, o);
          RobustnessRow& row = row_of(c, variant, motion);
          const auto& m = r.metrics;
          ++row.runs;
          row.worst_overshoot_m = std::max(row.worst_overshoot_m, m.cornering_overshoot_m);
          row.worst_path_accuracy_m = std::max(row.worst_path_accuracy_m, m.path_accuracy_m);
          row.worst_residual_m = std::max(row.worst_residual_m, m.residual_vibration_m);
          row.worst_max_deviation_m = std::max(row.worst_max_deviation_m, m.max_deviation_m);
          atp[fmt::format("{}|{}|{}|{}", c.factor, c.value, core::enum_name(variant), motion)].push_back(m.path_accuracy_m);
        }
      }
    }
  }
  for (auto& r : rows) r.median_path_accuracy_m = median(atp[fmt::format("{}|{}|{}|{}", r.factor, r.value, core::enum_name(r.variant), r.motion)]);
  return rows;
}

std::string robustness_tsv(const std::vector<RobustnessRow>& rows) {
  std::string out =
      "factor\tvalue\tvariant\tmotion\truns\tworst_CO_um\tworst_ATp_um\tmedian_ATp_um\tworst_residual_um\t"
      "worst_max_deviation_um\n";
  for (const auto& r : rows) {
    out += fmt::format("{}\t{:g}\t{}\t{}\t{}\t{:.1f}\t{:.1f}\t{:.1f}\t{:.1f}\t{:.1f}\n", r.factor, r.value, core::enum_name(r.variant),
                       r.motion, r.runs, r.worst_overshoot_m * 1e6, r.worst_path_accuracy_m * 1e6,
                       r.median_path_accuracy_m * 1e6, r.worst_residual_m * 1e6, r.worst_max_deviation_m * 1e6);
  }
  return out;
}

std::string robustness_markdown(const std::vector<RobustnessRow>& rows) {
  std::string out =
      "| factor | value | compensation | motion | runs | worst CO (µm) | worst AT_p (µm) | median AT_p (µm) | "
      "worst residual (µm) | worst max deviation (µm) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    out += fmt::format("| {} | {:g} | {} | {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} |\n", r.factor, r.value,
                       core::enum_name(r.variant), r.motion, r.runs, r.worst_overshoot_m * 1e6, r.worst_path_accuracy_m * 1e6,
                       r.median_path_accuracy_m * 1e6, r.worst_residual_m * 1e6, r.worst_max_deviation_m * 1e6);
  }
  return out;
}

}  // namespace stiffpath::simulation
