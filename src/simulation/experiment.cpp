// The test matrix of thesis §4.5 on the twin, each run in process with no files in between.
#include "stiffpath/simulation/experiment.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <map>
#include <sstream>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/job/task_source.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"
#include "stiffpath/simulation/cg_lever.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/simulation/compensation_variant.hpp"

namespace stiffpath::simulation {

namespace {
// The rectangle of the robot's measurement points (its table's rows), m.
compliance::GridBounds measured_region(const kinematics::Robot& robot) {
  const auto table = compliance::robot_table(robot);
  const compliance::GridBounds b = compliance::table_region(table);
  if (!(b.x_max > b.x_min) || !(b.y_max > b.y_min)) {
    throw Error(SourceLocation{table.source}, "the measurement points must spread over x and y to place test motions");
  }
  return b;
}

// The twin models are shared by robots with the same data, rows, model and geometry (oc-gu and oc-gl).
std::string data_key(const kinematics::Robot& r) {
  return fmt::format("{}|{}|{}|{}|{}", r.compliance.table.label(), r.compliance.rows, r.compliance.model.label(),
                     r.compliance.method ? core::enum_name(*r.compliance.method) : "auto", r.geometry_hash());
}
}  // namespace

TwinModels make_twin_models(const kinematics::Robot& robot, const ExperimentOptions& options) {
  TwinModels models;
  models.truth = make_true_compliance(robot, options.truth);
  const auto wants = [&](CompensationVariant v) {
    return std::find(options.variants.begin(), options.variants.end(), v) != options.variants.end();
  };
  CampaignFitOptions thesis_fit = options.fit;  // also the model the runs without compensation check the region with
  if (!thesis_fit.method) thesis_fit.method = compensation_fit_method(CompensationVariant::thesis);
  models.compensation = fit_compensation_model(*models.truth, robot, thesis_fit);
  if (wants(CompensationVariant::default_run)) {
    CampaignFitOptions fit = options.fit;
    fit.method = compensation_fit_method(CompensationVariant::default_run);
    models.compensation_default = fit_compensation_model(*models.truth, robot, fit);
  }
  if (!options.motions.empty()) {
    std::vector<double> xs, ys;  // the distinct coordinates of the measurement points: the grid lines
    for (const auto& r : compliance::robot_table(robot).rows) {
      auto add = [](std::vector<double>& v, double c) {
        if (std::none_of(v.begin(), v.end(), [c](double e) { return std::abs(e - c) < 1e-6; })) v.push_back(c);
      };
      add(xs, r.x_m);
      add(ys, r.y_m);
    }
    models.motions = test_motions(measured_region(robot), robot, xs, ys);
  }
  for (const auto& path : options.paths) models.motions.push_back(path);
  return models;
}

RunResult run_once(const RunSpec& spec, const kinematics::Robot& robot, const TwinModels& models,
                   const ExperimentOptions& options) {
  const TestMotion& motion = test_motion(models.motions, spec.motion);
  const bool default_variant = spec.variant == CompensationVariant::default_run;
  if (default_variant && !models.compensation_default) throw Error("the default variant's model was not made");
  SimulationOptions sim_options = options.simulation;
  if (options.cg_lever && !sim_options.cg_lever) sim_options.cg_lever = make_cg_lever(robot);

  // The run is the variant's job, as `run` would make it, with the twin's fitted model in place of the robot's.
  job::JobSpec job = variant_job(robot, spec.variant);
  job.model.given = options.oracle_model ? make_loaded_compliance(models.truth, sim_options.cg_lever)
                    : default_variant    ? models.compensation_default
                                         : models.compensation;
  job.model.given_label = options.oracle_model ? "the twin's C_true" : "the model fitted to the virtual campaign";
  job.gain = options.compensator.gain;
  job.check_limits = options.compensator.check_limits;
  job.damping_ratio = options.compensator.damping_ratio;
  job.plan.limits.max_acceleration_m_s2 = spec.acceleration_m_s2;
  job.plan.limits.max_jerk_m_s3 = motion::default_jerk_m_s3(job.plan.limits.max_acceleration_m_s2);
  job.plan.rate_hz = options.command_rate_hz;
  const job::PreparedJob prepared = job::prepare(std::move(job), job::Program::text(motion.gcode, motion.label));
  job::CommandStream commands(prepared);
  JointSource source = [&] { return commands.next(); };
  const SimulationResult sim = simulate(source, robot, models.truth, sim_options);
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
    std::vector<CompensationVariant> configs{CompensationVariant::without};
    for (const auto v : options.variants) {
      if (v != CompensationVariant::without) configs.push_back(v);
    }
    const double runs = static_cast<double>(options.robots.size() * configs.size() * motions.size() *
                                            options.accelerations_m_s2.size());
    for (const auto variant : configs) {
      for (const auto& motion : motions) {
        for (double a : options.accelerations_m_s2) {
          results.push_back(run_once({robot.name, motion, a, variant}, robot, twin, options));
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
      "cornering_overshoot_mm,residual_vibration_mm,peak_deflection_mm,variant,source\n";
  for (const auto& r : results) {
    const auto& m = r.metrics;
    out += fmt::format("{},{},{},{},{},{:g},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{:.6f},{:.6f},{},simulated\n",
                       r.spec.robot, r.rows, r.cg_label, r.spec.compensated() ? 1 : 0, r.spec.motion,
                       r.spec.acceleration_m_s2 / units::standard_gravity_m_s2, r.duration_s, m.length_m * 1e3, m.commanded_length_m * 1e3,
                       m.length_error_m * 1e3, m.deviation_area_m2 * 1e6, m.max_deviation_m * 1e3,
                       m.path_accuracy_m * 1e3, optional_mm(m, m.cornering_round_off_m),
                       optional_mm(m, m.cornering_overshoot_m), m.residual_vibration_m * 1e3, m.peak_deflection_m * 1e3,
                       r.spec.compensated() ? std::string(core::enum_name(r.spec.variant)) : std::string());
  }
  return out;
}

}  // namespace stiffpath::simulation
