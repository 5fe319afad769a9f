// The thesis's dynamic test matrix (§4.5) on the digital twin: plan → compensate → simulate → measure, in process.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/simulation/compensation_variant.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {

//! One test motion of fig. 4.7: its G-code (mm, robot frame) and the number of straight sides.
struct TestMotion {
  std::string name;   //!< "x", "y", "triangle", or a user's path
  std::string gcode;  //!< program text
  int sides = 1;
  std::string label;  //!< how errors name the program: "x_motion" …, or the user's file
};

//! The three motions of fig. 4.7 placed in a robot's measured rectangle `region` (m): x along the
//! rectangle's middle from its left to its right edge, y along its middle from bottom to top, and the
//! triangle (x_min + 0.15 w, y_min + 0.1 h), (x_max − 0.15 w, y_min + 0.1 h), (x_c, y_max − 0.1 h) —
//! exactly the thesis's coordinates on its rectangle [172.132, 272.132] × [−75, 75] mm. A motion that
//! passes a point `robot` refuses (reach or joint limits) is shrunk about the rectangle's centre by
//! steps of 10 % until it does not; throws stiffpath::Error when even 35 % of it does not fit.
//! Then the motions off the grid lines (`grid_x_m`, `grid_y_m`: the distinct coordinates of the measurement
//! points; empty: quarters of the rectangle), where interpolating models are least right: "y-mid-k", a y
//! line midway between grid columns k and k + 1 (every mid-cell); "x-mid", an x line midway between the
//! grid row nearest the middle and the next one up; "triangle-off", the triangle shifted right by a quarter
//! of the first column spacing (at most 7.5 % of the width) and up by a quarter row spacing (at most 5 % of
//! the height), so none of its sides lies along a grid line.
std::vector<TestMotion> test_motions(const compliance::GridBounds& region, const kinematics::Robot& robot,
                                     const std::vector<double>& grid_x_m = {}, const std::vector<double>& grid_y_m = {});
//! The motion called `name` among `motions`; throws stiffpath::Error naming the known ones.
const TestMotion& test_motion(const std::vector<TestMotion>& motions, const std::string& name);
//! A user's path from a G-code file given as "FILE[:SIDES]" (sides 1 … 12, default 1), named by the
//! file's stem. Throws stiffpath::Error for a file that cannot be read or a bad side count.
TestMotion user_motion(const std::string& file_and_sides);

//! One configuration and run of the matrix.
struct RunSpec {
  std::string robot = "oc-gu";      //!< the robot's name (a preset or a robot file's `name`)
  std::string motion = "y";
  double acceleration_m_s2 = 49.03325;  //!< path acceleration limit (5 g; jerk: default ramp time 5 ms)
  CompensationVariant variant = CompensationVariant::thesis;  //!< which compensation, or none
  [[nodiscard]] bool compensated() const noexcept { return variant != CompensationVariant::without; }
};

//! Everything shared by the runs of a matrix. Documented defaults.
struct ExperimentOptions {
  std::vector<std::string> robots{"oc-gu", "oc-gl", "sc-gu", "sc-gl"};  //!< presets or robot files
  std::vector<std::string> motions{"x", "y", "triangle"};  //!< of test_motions(); may be empty when paths are given
  std::vector<TestMotion> paths;       //!< users' own paths, run after the motions
  std::vector<double> accelerations_m_s2{9.80665, 19.6133, 29.41995, 39.2266, 49.03325};  //!< 1 … 5 g
  //! Compensations run besides "without": "thesis" (the thesis's quasi-static bilinear method, drawn in the
  //! figures) and "default" (what `run --method auto` does: dynamic compensation on a smoothed reference with the model cross-validation favours).
  std::vector<CompensationVariant> variants{CompensationVariant::thesis, CompensationVariant::default_run};
  bool cg_lever = true;  //!< the CG's height tilts the platform (make_cg_lever); false: the CG at G
  //! Compensate with C_true (+ the CG lever) itself instead of the fitted model: the error budget's case
  //! without model error.
  bool oracle_model = false;
  TrueComplianceOptions truth;         //!< C_true per robot data (table, rows, geometry)
  CampaignFitOptions fit;              //!< compensation model per robot data (virtual campaign + fit)
  compensation::CompensatorOptions compensator;  //!< gain etc.; `enabled` is set per run
  SimulationOptions simulation;
  double command_rate_hz = 2000.0;  //!< rate of the planned samples and joint commands (the thesis's 2 kHz loop)
};

//! One row of the experiment's results.
struct RunResult {
  RunSpec spec;
  std::string rows;      //!< the robot's rows of its table ("OC"/"SC" for the presets)
  std::string cg_label;  //!< "G_U"/"G_L"
  RunMetrics metrics;
  double duration_s = 0.0;
};

//! The plant's true compliance and the compensation model of one robot's data, made once and shared by
//! the robots with the same data and geometry, and the robot's test motions.
struct TwinModels {
  std::shared_ptr<const compliance::Model> truth;
  std::shared_ptr<const compliance::Model> compensation;          //!< the "thesis" variant's model
  std::shared_ptr<const compliance::Model> compensation_default;  //!< the "default" variant's (null if not run)
  std::vector<TestMotion> motions;  //!< test_motions() in the robot's measured rectangle, then options.paths
};
TwinModels make_twin_models(const kinematics::Robot& robot, const ExperimentOptions& options = {});

//! Plans, compensates (or not), simulates and measures one run of `robot`. Throws stiffpath::Error
//! when a command is refused by the compensator (naming the reason) or the run cannot be measured.
RunResult run_once(const RunSpec& spec, const kinematics::Robot& robot, const TwinModels& models,
                   const ExperimentOptions& options = {});

//! Runs the whole matrix robots × {without, variants…} × motions × accelerations (180 runs by default),
//! models made once per robot data.
//! `progress`, when set, is called with the fraction of runs done after each run.
std::vector<RunResult> run_experiment(const ExperimentOptions& options = {},
                                      const std::function<void(double)>& progress = {});

//! CSV header and one line per run (units in the column names, lengths in mm); the column variant names
//! the compensation variant (empty without), and the last column, source, says "simulated" on every row,
//! so that figures drawn from the file say so.
std::string experiment_csv(const std::vector<RunResult>& results);

//! Plain-text tables (Markdown), one per acceleration, each with one line per robot × motion:
//! length error and maximum deviation without → with compensation and the share removed
//! (1 − |with|/|without|), deviation area and residual vibration.
std::string experiment_summary(const std::vector<RunResult>& results);

}  // namespace stiffpath::simulation
