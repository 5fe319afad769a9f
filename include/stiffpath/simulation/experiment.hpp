// The thesis's dynamic test matrix (§4.5) on the digital twin: plan → compensate → simulate → measure, in process.
#pragma once

#include <string>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/job.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {

//! One test motion of fig. 4.7: its G-code (mm, robot frame) and the number of straight sides.
struct TestMotion {
  std::string name;   //!< "x", "y", "triangle"
  std::string gcode;  //!< program text, the same as examples/<name>_motion.gcode / triangle.gcode
  int sides = 1;
};

//! The three motions of fig. 4.7: x (100 mm along y = 0), y (150 mm along x = 222.132 mm), triangle.
const std::vector<TestMotion>& test_motions();
//! The motion called `name`; throws stiffpath::Error naming the known ones.
const TestMotion& test_motion(const std::string& name);

//! One configuration and run of the matrix.
struct RunSpec {
  std::string mechanism = "oc-gu";  //!< preset (oc-gu, oc-gl, sc-gu, sc-gl)
  std::string motion = "y";
  double acceleration_g = 5.0;      //!< path acceleration limit, in g (jerk: default ramp time 5 ms)
  bool compensated = true;
};

//! Everything shared by the runs of a matrix. Documented defaults.
struct ExperimentOptions {
  std::vector<std::string> mechanisms{"oc-gu", "oc-gl", "sc-gu", "sc-gl"};
  std::vector<std::string> motions{"x", "y", "triangle"};
  std::vector<double> accelerations_g{1, 2, 3, 4, 5};
  TrueComplianceOptions truth;         //!< C_true per build
  CampaignFitOptions fit;              //!< compensation model per build (virtual campaign + thesis fit)
  compensation::CompensatorOptions compensator;  //!< gain etc.; `enabled` is set per run
  SimulationOptions simulation;
  double command_rate_hz = 2000.0;  //!< rate of the planned samples and joint commands (the thesis's 2 kHz loop)
};

//! One row of the experiment's results.
struct RunResult {
  RunSpec spec;
  std::string build;     //!< "OC"/"SC"
  std::string cg_label;  //!< "G_U"/"G_L"
  RunMetrics metrics;
  double duration_s = 0.0;
};

//! The plant's true compliance and the compensation model of one build, made once and shared by runs.
struct TwinModels {
  std::shared_ptr<const compliance::Model> truth;
  std::shared_ptr<const compliance::Model> compensation;
};
TwinModels make_twin_models(const std::string& build, const ExperimentOptions& options = {});

//! Plans, compensates (or not), simulates and measures one run. Throws stiffpath::Error when a
//! command is refused by the compensator (naming the reason) or the run cannot be measured.
RunResult run_once(const RunSpec& spec, const TwinModels& models, const ExperimentOptions& options = {});

//! Runs the whole matrix mechanisms × {without, with} × motions × accelerations (120 runs by default),
//! models made once per build.
std::vector<RunResult> run_experiment(const ExperimentOptions& options = {});

//! CSV header and one line per run (units in the column names, lengths in mm).
std::string experiment_csv(const std::vector<RunResult>& results);

//! A plain-text table (Markdown) with one line per mechanism × motion at the highest acceleration run:
//! length error and maximum deviation without → with compensation and the share removed
//! (1 − |with|/|without|), deviation area and residual vibration.
std::string experiment_summary(const std::vector<RunResult>& results);

}  // namespace stiffpath::simulation
