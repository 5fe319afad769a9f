// The test matrix of thesis §4.5 on the twin, each run in process with no files in between.
#include "stiffpath/simulation/experiment.hpp"

#include <fmt/format.h>
#include <map>
#include <sstream>

#include "stiffpath/compensation/job.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/mechanism_spec.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::simulation {

const std::vector<TestMotion>& test_motions() {
  static const std::vector<TestMotion> motions{
      {"x", "G21 G90 G17 G94\nG61\nG0 X172.132 Y0\nM3 S1000\nG1 X272.132 F120000\nM5\nM2\n", 1},
      {"y", "G21 G90 G17 G94\nG61\nG0 X222.132 Y-75\nM3 S1000\nG1 Y75 F120000\nM5\nM2\n", 1},
      {"triangle",
       "G21 G90 G17 G94\nG61\nG0 X187.132 Y-60\nM3 S1000\nG1 X257.132 Y-60 F120000\nG1 X222.132 Y60\n"
       "G1 X187.132 Y-60\nM5\nM2\n",
       3},
  };
  return motions;
}

const TestMotion& test_motion(const std::string& name) {
  for (const auto& m : test_motions()) {
    if (m.name == name) return m;
  }
  throw Error(fmt::format("unknown test motion '{}' (known: x, y, triangle)", name));
}

TwinModels make_twin_models(const std::string& build, const ExperimentOptions& options) {
  TwinModels models;
  models.truth = make_true_compliance(build, options.truth);
  models.compensation = fit_compensation_model(*models.truth, build, options.fit);
  return models;
}

RunResult run_once(const RunSpec& spec, const TwinModels& models, const ExperimentOptions& options) {
  const kinematics::MechanismSpec mechanism = kinematics::load_mechanism(spec.mechanism);
  const TestMotion& motion = test_motion(spec.motion);
  motion::PlanOptions plan;
  plan.limits.max_acceleration_m_s2 = spec.acceleration_g * units::standard_gravity_m_s2;
  plan.rate_hz = options.command_rate_hz;
  plan.limits.max_jerk_m_s3 = motion::default_jerk_m_s3(plan.limits.max_acceleration_m_s2);
  std::istringstream program(motion.gcode);
  const std::string label = fmt::format("{}_motion", motion.name);
  motion::TrajectoryStream stream(program, label, plan);
  compensation::CompensatorOptions copts = options.compensator;
  copts.enabled = spec.compensated;
  const compensation::Compensator compensator(mechanism, models.compensation, copts);
  JointSource source = [&]() -> std::optional<compensation::JointRecord> {
    const auto sample = stream.next();
    if (!sample) return std::nullopt;
    const compensation::JointCommand c = compensator.step(compensation::to_task_sample(*sample));
    if (c.status != compensation::Status::ok) compensation::throw_refusal(c, compensator, label);
    compensation::JointRecord r;
    r.t_s = c.t_s;
    r.q_rad = c.q_rad;
    r.qd_rad_s = c.qd_rad_s;
    r.qdd_rad_s2 = c.qdd_rad_s2;
    r.target_m = c.target_m;
    r.command_m = c.command_m;
    r.force_N = c.force_N;
    r.laser_on = c.laser_on;
    r.line = c.line;
    return r;
  };
  const SimulationResult sim = simulate(source, mechanism, models.truth, options.simulation);
  RunResult out;
  out.spec = spec;
  out.build = mechanism.build;
  out.cg_label = mechanism.cg_label;
  out.metrics = measure_run(sim, motion.sides);
  out.duration_s = sim.duration_s;
  return out;
}

std::vector<RunResult> run_experiment(const ExperimentOptions& options) {
  std::map<std::string, TwinModels> models;  // one truth and one fitted model per build
  std::vector<RunResult> results;
  for (const auto& name : options.mechanisms) {
    const std::string build = kinematics::load_mechanism(name).build;
    if (!models.count(build)) models.emplace(build, make_twin_models(build, options));
    for (bool compensated : {false, true}) {
      for (const auto& motion : options.motions) {
        for (double g : options.accelerations_g) {
          results.push_back(run_once({name, motion, g, compensated}, models.at(build), options));
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
      "mechanism,build,cg,compensated,motion,acceleration_g,duration_s,length_mm,commanded_length_mm,"
      "length_error_mm,deviation_area_mm2,max_deviation_mm,path_accuracy_mm,cornering_round_off_mm,"
      "cornering_overshoot_mm,residual_vibration_mm,peak_deflection_mm\n";
  for (const auto& r : results) {
    const auto& m = r.metrics;
    out += fmt::format("{},{},{},{},{},{:g},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{:.6f},{:.6f}\n",
                       r.spec.mechanism, r.build, r.cg_label, r.spec.compensated ? 1 : 0, r.spec.motion,
                       r.spec.acceleration_g, r.duration_s, m.length_m * 1e3, m.commanded_length_m * 1e3,
                       m.length_error_m * 1e3, m.deviation_area_m2 * 1e6, m.max_deviation_m * 1e3,
                       m.path_accuracy_m * 1e3, optional_mm(m, m.cornering_round_off_m),
                       optional_mm(m, m.cornering_overshoot_m), m.residual_vibration_m * 1e3, m.peak_deflection_m * 1e3);
  }
  return out;
}

}  // namespace stiffpath::simulation
