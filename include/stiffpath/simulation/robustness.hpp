// How the compensation holds up when the twin is not what the compensation assumes: one factor at a time, over seeds.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::simulation {

//! The sweep of `stiffpath experiment --robustness`. Each condition changes one factor from the nominal
//! twin and runs every motion × variant × seed; seed k sets C_true's perturbation seed k and the virtual
//! campaign's noise seed 1000 + k. Documented defaults.
struct RobustnessOptions {
  std::string robot = "oc-gu";
  std::vector<std::string> motions{"triangle-off", "y-mid-2"};  //!< of test_motions()
  double acceleration_m_s2 = 49.03325;  //!< 5 g
  std::vector<CompensationVariant> variants{CompensationVariant::without, CompensationVariant::thesis,
                                            CompensationVariant::default_run};
  int seeds = 10;                                                  //!< truth/campaign seeds 1 … seeds
  std::vector<double> damping_ratios{0.01, 0.02, 0.05, 0.1, 0.2};   //!< the tip's ζ (nominal: base's)
  std::vector<double> mass_errors{-0.25, 0.25};                      //!< plant mass / believed mass − 1
  std::vector<double> servo_bandwidths_hz{50.0, 200.0};
  std::vector<double> noise_sigmas_m{0.0, 23e-6};                     //!< campaign noise σ per coordinate
  ExperimentOptions base;   //!< the nominal twin (plant, C_true, campaign, compensator); robots/motions ignored
  int max_runs = 3000;      //!< refuse a sweep with more runs (≈ 10–25 ms each in a release build)
};

//! One condition × variant × motion, over the seeds (lengths in m).
struct RobustnessRow {
  std::string factor;  //!< "nominal", "damping_ratio", "mass_error", "servo_bandwidth_hz", "noise_um"
  double value = 0.0;
  CompensationVariant variant = CompensationVariant::without;
  std::string motion;
  int runs = 0;
  double worst_overshoot_m = 0.0;     //!< ISO 9283 CO, largest over seeds (0 for a line)
  double worst_path_accuracy_m = 0.0; //!< ISO 9283 AT_p
  double worst_residual_m = 0.0;      //!< residual vibration after the stop
  double worst_max_deviation_m = 0.0; //!< deviation from linearity (§4.7), largest over sides
  double median_path_accuracy_m = 0.0;
};

//! The number of runs `options` asks for.
int robustness_run_count(const RobustnessOptions& options);

//! Runs the sweep. Throws stiffpath::Error for bad options or more than max_runs runs.
std::vector<RobustnessRow> run_robustness(const RobustnessOptions& options);

//! Tab-separated table with a header (µm), one line per row.
std::string robustness_tsv(const std::vector<RobustnessRow>& rows);
//! The same as a Markdown table.
std::string robustness_markdown(const std::vector<RobustnessRow>& rows);

}  // namespace stiffpath::simulation
