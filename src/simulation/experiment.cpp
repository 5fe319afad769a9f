// The test matrix of thesis §4.5 on the twin, each run in process with no files in between.
#include "stiffpath/simulation/experiment.hpp"

#include <fmt/format.h>
#include <map>
#include <sstream>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::simulation {

namespace {
// The rectangle of the robot's measurement points (its table's rows), m.
compliance::GridBounds measured_region(const kinematics::Robot& robot) {
  const auto table = compliance::robot_table(robot);
  compliance::GridBounds b{1e300, -1e300, 1e300, -1e300};
  for (const auto& r : table.rows) {
    b.x_min = std::min(b.x_min, r.x_m);
    b.x_max = std::max(b.x_max, r.x_m);
    b.y_min = std::min(b.y_min, r.y_m);
    b.y_max = std::max(b.y_max, r.y_m);
  }
  if (!(b.x_max > b.x_min) || !(b.y_max > b.y_min)) {
    throw Error(SourceLocation{table.source}, "the measurement points must spread over x and y to place test motions");
  }
  return b;
}

// The twin models are shared by robots with the same data, rows, model and geometry (oc-gu and oc-gl).
std::string data_key(const kinematics::Robot& r) {
  return fmt::format("{}|{}|{}|{}|{}", r.compliance.table.label(), r.compliance.rows, r.compliance.model.label(),
                     r.compliance.method, r.geometry_hash());
}
}  // namespace

TwinModels make_twin_models(const kinematics::Robot& robot, const ExperimentOptions& options) {
  TwinModels models;
  models.truth = make_true_compliance(robot, options.truth);
  models.compensation = fit_compensation_model(*models.truth, robot, options.fit);
  if (!options.motions.empty()) models.motions = test_motions(measured_region(robot), robot);
  for (const auto& path : options.paths) models.motions.push_back(path);
  return models;
}

RunResult run_once(const RunSpec& spec, const kinematics::Robot& robot, const TwinModels& models,
                   const ExperimentOptions& options) {
  const TestMotion& motion = test_motion(models.motions, spec.motion);
  motion::PlanOptions plan;
  plan.limits.max_acceleration_m_s2 = spec.acceleration_g * units::standard_gravity_m_s2;
  plan.rate_hz = options.command_rate_hz;
  plan.limits.max_jerk_m_s3 = motion::default_jerk_m_s3(plan.limits.max_acceleration_m_s2);
  std::istringstream program(motion.gcode);
  motion::TrajectoryStream stream(program, motion.label, plan);
  compensation::CompensatorOptions copts = options.compensator;
  copts.enabled = spec.compensated;
  const compensation::Compensator compensator(robot, models.compensation, copts);
  JointSource source = [&]() -> std::optional<compensation::JointCommand> {
    const auto sample = stream.next();
    if (!sample) return std::nullopt;
    const compensation::JointCommand c = compensator.step(job::to_task_sample(*sample));
    if (c.status != compensation::Status::ok) job::throw_refusal(c, compensator, motion.label);
    return c;
  };
  const SimulationResult sim = simulate(source, robot, models.truth, options.simulation);
  RunResult out;
  out.spec = spec;
  out.rows = robot.compliance.rows;
  out.cg_label = robot.cg_label;
  out.metrics = measure_run(sim, motion.sides);
  out.duration_s = sim.duration_s;
  return out;
}

std::vector<RunResult> run_experiment(const ExperimentOptions& options, const std::function<void(double)>& progress) {
  std::map<std::string, TwinModels> models;  // one truth and one fitted model per robot data
  std::vector<RunResult> results;
  for (const auto& name : options.robots) {
    const kinematics::Robot robot = kinematics::load_robot(name);
    const std::string key = data_key(robot);
    if (!models.count(key)) models.emplace(key, make_twin_models(robot, options));
    const TwinModels& twin = models.at(key);
    std::vector<std::string> motions = options.motions;
    for (const auto& path : options.paths) motions.push_back(path.name);
    const double runs = static_cast<double>(options.robots.size() * 2 * motions.size() * options.accelerations_g.size());
    for (bool compensated : {false, true}) {
      for (const auto& motion : motions) {
        for (double g : options.accelerations_g) {
          results.push_back(run_once({robot.name, motion, g, compensated}, robot, twin, options));
          if (progress) progress(static_cast<double>(results.size()) / runs);
        }
      }
    }
  }
  return results;
}

namespace {
// A cornering metric in mm, or an empty CSV cell for a path without corners.
std::string optional_mm(const RunMetrics& m, double value_m) {
  return m.corners == 0 ? std::string() : fmt::format("{:.6f}", value_m * 1e3);
}
}  // namespace

std::string experiment_csv(const std::vector<RunResult>& results) {
  std::string out =
      "robot,rows,cg,compensated,motion,acceleration_g,duration_s,length_mm,commanded_length_mm,"
      "length_error_mm,deviation_area_mm2,max_deviation_mm,path_accuracy_mm,cornering_round_off_mm,"
      "cornering_overshoot_mm,residual_vibration_mm,peak_deflection_mm,source\n";
  for (const auto& r : results) {
    const auto& m = r.metrics;
    out += fmt::format("{},{},{},{},{},{:g},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{:.6f},{:.6f},simulated\n",
                       r.spec.robot, r.rows, r.cg_label, r.spec.compensated ? 1 : 0, r.spec.motion,
                       r.spec.acceleration_g, r.duration_s, m.length_m * 1e3, m.commanded_length_m * 1e3,
                       m.length_error_m * 1e3, m.deviation_area_m2 * 1e6, m.max_deviation_m * 1e3,
                       m.path_accuracy_m * 1e3, optional_mm(m, m.cornering_round_off_m),
                       optional_mm(m, m.cornering_overshoot_m), m.residual_vibration_m * 1e3, m.peak_deflection_m * 1e3);
  }
  return out;
}

}  // namespace stiffpath::simulation
