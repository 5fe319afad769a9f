// `stiffpath geometry fit|plan|simulate`: calibrate a robot's geometry from instrument readings, plan the poses, rehearse.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Geometry>

#include <filesystem>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/kinematics/robot_json.hpp"
#include "stiffpath/calibration/geometry_fit.hpp"
#include "stiffpath/calibration/geometry_plan.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/report/geometry_plots.hpp"

namespace stiffpath::cli {

namespace {
struct ToleranceOptions {
  double noise_um = 11.5;
  double actuator_mm = 0.2;
  double link_mm = 0.3;
  double zero_deg = 0.1;
  calibration::GeometryFitSettings settings() const {
    calibration::GeometryFitSettings s;
    s.noise_sigma_m = units::um_to_m(noise_um);
    s.actuator_tolerance_m = units::mm_to_m(actuator_mm);
    s.link_tolerance_m = units::mm_to_m(link_mm);
    s.zero_tolerance_rad = units::deg_to_rad(zero_deg);
    return s;
  }
};

void add_tolerance_flags(CLI::App* cmd, ToleranceOptions& o) {
  cmd->add_option("--noise-um", o.noise_um, "Sigma of one instrument coordinate (um); 11.5 = +-23 um at 2 sigma")
      ->capture_default_str()
      ->check(within(0.01, 10000.0, "um"));
  cmd->add_option("--actuator-tolerance-mm", o.actuator_mm, "How far the actuators may be off the robot file (mm)")
      ->capture_default_str()
      ->check(within(1e-4, 100.0, "mm"));
  cmd->add_option("--link-tolerance-mm", o.link_mm, "How far the links may be off the robot file (mm)")
      ->capture_default_str()
      ->check(within(1e-4, 100.0, "mm"));
  cmd->add_option("--zero-tolerance-deg", o.zero_deg, "How far the joint zeros may be off (deg)")
      ->capture_default_str()
      ->check(within(1e-5, 90.0, "deg"));
}

// ---- fit ----
struct FitOptions {
  std::string readings;
  std::string robot;
  std::string output;
  std::string report_dir;  // default: <output stem>_report beside the output
  ToleranceOptions tolerances;
  std::string style = "screen";
  bool no_plots = false;
  bool json = false;
};

double edge(int k, double si) { return si * calibration::parameter_unit_factor(k); }

nlohmann::json report_json(const FitOptions& o, const kinematics::Robot& robot, const calibration::GeometryFitResult& fit,
                           const std::vector<std::string>& notes) {
  nlohmann::json params = nlohmann::json::array();
  for (int k = 0; k < calibration::kGeometryParameters; ++k) {
    const auto& p = fit.parameters[static_cast<std::size_t>(k)];
    if (!p.applicable) continue;
    params.push_back({{"name", p.name},
                      {"nominal", tidy(edge(k, p.nominal))},
                      {"value", tidy(edge(k, p.value))},
                      {"change", tidy(edge(k, p.value - p.nominal))},
                      {"sigma", tidy(edge(k, p.sigma))},
                      {"held", p.fixed}});
  }
  nlohmann::json undetermined = nlohmann::json::array();
  for (const auto& d : fit.undetermined) {
    nlohmann::json shares = nlohmann::json::object();
    for (const auto& [name, v] : d.shares) shares[name] = tidy(v);
    undetermined.push_back({{"parameters", shares}, {"singular_value_over_noise", tidy(d.singular_value_over_noise)}});
  }
  nlohmann::json residuals = nlohmann::json::array();
  const int dims = fit.spatial ? 3 : 2;
  for (const auto& r : fit.residuals) {
    nlohmann::json before = nlohmann::json::array(), after = nlohmann::json::array();
    for (int d = 0; d < dims; ++d) {
      before.push_back(tidy(r.before_m(d) * 1e6));
      after.push_back(tidy(r.after_m(d) * 1e6));
    }
    residuals.push_back({{"line", r.line},
                         {"theta1_deg", tidy(units::rad_to_deg(r.q_rad.x()))},
                         {"theta2_deg", tidy(units::rad_to_deg(r.q_rad.y()))},
                         {"before_um", before},
                         {"after_um", after}});
  }
  nlohmann::json rotation = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) rotation.push_back({tidy(fit.instrument.rotation(i, 0)), tidy(fit.instrument.rotation(i, 1)), tidy(fit.instrument.rotation(i, 2))});
  return {{"format", "stiffpath-geometry-fit"},
          {"robot", robot.name},
          {"robot_file", robot.source()},
          {"readings", o.readings},
          {"output", o.output},
          {"reading_count", fit.readings},
          {"instrument", {{"spatial", fit.spatial}, {"mirrored", fit.mirrored}, {"rotation", rotation},
                          {"translation_mm", {tidy(fit.instrument.translation_m.x() * 1e3), tidy(fit.instrument.translation_m.y() * 1e3),
                                              tidy(fit.instrument.translation_m.z() * 1e3)}}}},
          {"solver", {{"stop", core::to_string(fit.stop)}, {"iterations", fit.iterations}, {"fitted_parameters", fit.fitted}}},
          {"rms_before_um", tidy(fit.rms_before_m * 1e6)},
          {"rms_after_um", tidy(fit.rms_after_m * 1e6)},
          {"max_before_um", tidy(fit.max_before_m * 1e6)},
          {"max_after_um", tidy(fit.max_after_m * 1e6)},
          {"sigma_estimated_um", tidy(fit.sigma_estimated_m * 1e6)},
          {"noise_assumed_um", o.tolerances.noise_um},
          {"parameters", params},
          {"undetermined", undetermined},
          {"residuals", residuals},
          {"notes", notes}};
}

void fit(const FitOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  core::check_distinct_files(robot_inputs(robot, false, {{"readings", o.readings}}), {{"-o", o.output}});
  const auto readings = calibration::load_geometry_readings(o.readings);
  const std::filesystem::path out(o.output);
  const std::filesystem::path dir = o.report_dir.empty() ? out.parent_path() / (out.stem().string() + "_report") : std::filesystem::path(o.report_dir);
  core::check_output_directory(dir);
  const auto result = calibration::fit_geometry(robot, readings, o.tolerances.settings());
  std::vector<std::string> notes;
  const kinematics::Robot calibrated = calibration::calibrated_robot(robot, result, &notes);
  const std::string text = kinematics::to_json(calibrated).dump(2) + "\n";
  (void)kinematics::parse_robot(text, core::DataRef{o.output, false});  // what we write, every command reads
  const nlohmann::json report = report_json(o, robot, result, notes);
  core::create_output_directory(dir);
  core::write_file_atomically(dir / "geometry_fit.json", report.dump(2) + "\n");
  std::string figure;
  if (!o.no_plots) {
    if (report::gnuplot_available()) {
      report::plot_geometry_residuals(dir, "geometry_residuals", result,
                                      fmt::format("robot {}: {} readings of {}", robot.name, result.readings, o.readings),
                                      report::parse_style(o.style));
      figure = (dir / "geometry_residuals.svg").string();
    } else {
      notes.push_back("gnuplot not found: the figure was skipped");
    }
  }
  core::write_file_atomically(out, text);
  if (o.json) {
    print_json(report);
    return;
  }
  fmt::print("geometry of robot {} from {} readings ({}{}): RMS misfit {:.1f} um -> {:.1f} um per coordinate, largest "
             "{:.1f} -> {:.1f} um; residual sigma {:.1f} um ({} parameters fitted, {})\n",
             robot.name, result.readings, result.spatial ? "x, y, z" : "x, y", result.mirrored ? ", mirrored frame" : "",
             result.rms_before_m * 1e6, result.rms_after_m * 1e6, result.max_before_m * 1e6, result.max_after_m * 1e6,
             result.sigma_estimated_m * 1e6, result.fitted, core::to_string(result.stop));
  fmt::print("{:<28} {:>12} {:>12} {:>10} {:>9}\n", "parameter", "robot file", "calibrated", "change", "sigma");
  for (int k = 0; k < calibration::kRobotParameters; ++k) {
    const auto& p = result.parameters[static_cast<std::size_t>(k)];
    fmt::print("{:<28} {:>12.4f} {:>12.4f} {:>+10.4f} {:>9}\n", p.name, edge(k, p.nominal), edge(k, p.value),
               edge(k, p.value - p.nominal), p.fixed ? "held" : fmt::format("{:.4f}", edge(k, p.sigma)));
  }
  for (const auto& d : result.undetermined) {
    std::string parts;
    for (const auto& [name, v] : d.shares) parts += fmt::format("{}{:+.2f} {}", parts.empty() ? "" : ", ", v, name);
    fmt::print("not separable by these readings (singular value {:.2g} x noise): {}\n", d.singular_value_over_noise, parts);
  }
  for (const auto& n : notes) fmt::print("note: {}\n", n);
  fmt::print("wrote {} and {}{}\n", o.output, (dir / "geometry_fit.json").string(), figure.empty() ? "" : " and " + figure);
}

// ---- plan ----
struct PlanOptions {
  std::string robot;
  int poses = 30;
  std::vector<double> region_mm;
  std::string output;
  std::string plot_dir;
  ToleranceOptions tolerances;
  std::string style = "screen";
  bool json = false;
};

void plan(const PlanOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  core::check_distinct_files(robot_inputs(robot, false), {{"-o", o.output}});
  calibration::GeometryPlanSettings s;
  s.poses = o.poses;
  s.fit = o.tolerances.settings();
  if (!o.region_mm.empty()) {
    const auto& r = o.region_mm;
    if (!(r[1] > r[0] && r[3] > r[2])) throw Error("--region-mm: give XMIN XMAX YMIN YMAX with XMAX > XMIN and YMAX > YMIN");
    s.region = compliance::GridBounds{r[0] * 1e-3, r[1] * 1e-3, r[2] * 1e-3, r[3] * 1e-3};
  }
  if (!o.plot_dir.empty()) core::check_output_directory(o.plot_dir);
  const auto result = calibration::plan_geometry_poses(robot, s);
  calibration::save_geometry_plan(result, o.output);
  if (!o.plot_dir.empty()) {
    core::create_output_directory(o.plot_dir);
    report::plot_geometry_plan(o.plot_dir, "geometry_plan", result, robot,
                               fmt::format("robot {}: {} poses for a geometry calibration", robot.name, result.poses.size()),
                               report::parse_style(o.style));
  }
  nlohmann::json sigma = nlohmann::json::object();
  for (int k = 0; k < calibration::kRobotParameters; ++k) {
    const double v = result.predicted_sigma[static_cast<std::size_t>(k)];
    if (v > 0.0) sigma[calibration::parameter_name(k)] = tidy(edge(k, v));
  }
  if (o.json) {
    print_json({{"robot", robot.name}, {"output", o.output}, {"poses", result.poses.size()},
                {"candidates", result.reachable.size()}, {"lattice_mm", tidy(result.lattice_step_m * 1e3)},
                {"min_separation_mm", tidy(result.min_separation_m * 1e3)}, {"held", result.held},
                {"predicted_sigma", sigma}, {"noise_um", o.tolerances.noise_um}, {"log_det", tidy(result.log_det)}});
    return;
  }
  fmt::print("{} poses for robot {} (of {} reachable candidates on a {:.1f} mm lattice, at least {:.1f} mm apart); "
             "the readings cannot separate and the fit will hold: {}\n",
             result.poses.size(), robot.name, result.reachable.size(), result.lattice_step_m * 1e3,
             result.min_separation_m * 1e3, fmt::join(result.held, ", "));
  fmt::print("predicted sigma with {:.1f} um per coordinate, planar readings:", o.tolerances.noise_um);
  for (int k = 0; k < calibration::kRobotParameters; ++k) {
    const double v = result.predicted_sigma[static_cast<std::size_t>(k)];
    if (v > 0.0) fmt::print(" {} {:.4f}", calibration::parameter_name(k), edge(k, v));
  }
  fmt::print("\nwrote {}{}\n", o.output, o.plot_dir.empty() ? "" : " and " + (std::filesystem::path(o.plot_dir) / "geometry_plan.svg").string());
}

// ---- simulate ----
struct SimulateOptions {
  std::string truth;
  std::string poses;
  std::string output;
  double noise_um = 11.5;
  double yaw_deg = 30.0;
  double tilt_deg = 0.0;
  std::vector<double> shift_mm{500.0, -300.0, 0.0};
  bool spatial = false;
  int readings = 1;
  std::uint64_t seed = 1;
};

void simulate(const SimulateOptions& o) {
  const auto truth = kinematics::load_robot(o.truth);
  core::check_distinct_files(robot_inputs(truth, false, {{"--poses", o.poses}}), {{"-o", o.output}});
  const auto q = calibration::load_pose_angles(o.poses);
  calibration::GeometryRehearsal r;
  r.frame.rotation = (Eigen::AngleAxisd(units::deg_to_rad(o.yaw_deg), Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(units::deg_to_rad(o.tilt_deg), Eigen::Vector3d::UnitX()))
                         .toRotationMatrix();
  r.frame.translation_m = Eigen::Vector3d(o.shift_mm[0], o.shift_mm[1], o.shift_mm[2]) * 1e-3;
  r.noise_sigma_m = units::um_to_m(o.noise_um);
  r.readings_per_pose = o.readings;
  r.spatial = o.spatial;
  r.seed = o.seed;
  if (!o.spatial && o.tilt_deg != 0.0) throw Error("--tilt-deg needs --z (a tilted instrument reads z as well)");
  calibration::GeometryReadings readings;
  try {
    readings = calibration::simulate_geometry_readings(truth.geometry, q, r);
  } catch (const Error& e) {
    throw Error(SourceLocation{o.poses}, fmt::format("robot {}: {}", truth.name, e.message()));
  }
  calibration::save_geometry_readings(readings, o.output);
  fmt::print("{} readings of robot {} ({} poses of {}), noise sigma {:.1f} um, instrument turned {:g} deg{} and shifted "
             "({:g}, {:g}, {:g}) mm, seed {}\nwrote {}\n",
             readings.rows.size(), truth.name, q.size(), o.poses, o.noise_um, o.yaw_deg,
             o.spatial ? fmt::format(", tilted {:g} deg", o.tilt_deg) : "", o.shift_mm[0], o.shift_mm[1], o.shift_mm[2],
             o.seed, o.output);
}
}  // namespace

void add_geometry_command(CLI::App& app) {
  auto* geometry = app.add_subcommand("geometry", "Calibrate a robot's geometry from readings of its tool point");
  geometry->require_subcommand(1);

  auto f = std::make_shared<FitOptions>();
  auto* fit_cmd = geometry->add_subcommand("fit", "Fit actuators, links and joint zeros (and the instrument's frame) to readings");
  fit_cmd->add_option("readings", f->readings, "CSV: theta1_deg,theta2_deg,x_mm,y_mm[,z_mm][,reading]")->required();
  add_robot_flag(fit_cmd, f->robot);
  fit_cmd->add_option("-o,--output", f->output, "Calibrated robot file to write")->required();
  fit_cmd->add_option("--report-dir", f->report_dir, "Folder for geometry_fit.json and the figure (default: <output>_report)");
  add_tolerance_flags(fit_cmd, f->tolerances);
  fit_cmd->add_option("--style", f->style, "Figure style: screen or paper")->capture_default_str();
  fit_cmd->add_flag("--no-plots", f->no_plots, "Skip the figure");
  fit_cmd->add_flag("--json", f->json, "Print the report as JSON");
  fit_cmd->callback([f] { fit(*f); });

  auto p = std::make_shared<PlanOptions>();
  auto* plan_cmd = geometry->add_subcommand("plan", "Choose the joint poses that determine the geometry best");
  add_robot_flag(plan_cmd, p->robot);
  plan_cmd->add_option("--readings", p->poses, "How many poses")->capture_default_str()->check(within(4, calibration::kMaxPlannedPoses, ""));
  plan_cmd->add_option("--region-mm", p->region_mm, "Only poses in XMIN XMAX YMIN YMAX (robot frame, mm)")
      ->expected(4)
      ->check(within(-1e4, 1e4, "mm"));
  plan_cmd->add_option("-o,--output", p->output, "Poses CSV to write (pose,theta1_deg,theta2_deg,x_mm,y_mm,...)")->required();
  plan_cmd->add_option("--plot-dir", p->plot_dir, "Also draw the reachable region and the poses (geometry_plan.svg) here");
  add_tolerance_flags(plan_cmd, p->tolerances);
  plan_cmd->add_option("--style", p->style, "Figure style: screen or paper")->capture_default_str();
  plan_cmd->add_flag("--json", p->json, "Print a JSON summary");
  plan_cmd->callback([p] { plan(*p); });

  auto s = std::make_shared<SimulateOptions>();
  auto* sim_cmd = geometry->add_subcommand("simulate", "Rehearse: what an instrument would read at the poses of a known robot");
  sim_cmd->add_option("--truth", s->truth, "Robot file (or preset) whose geometry is the truth")->required();
  sim_cmd->add_option("--poses", s->poses, "Poses CSV (theta1_deg, theta2_deg), e.g. from geometry plan")->required();
  sim_cmd->add_option("-o,--output", s->output, "Readings CSV to write")->required();
  sim_cmd->add_option("--noise-um", s->noise_um, "Sigma of every coordinate (um)")->capture_default_str()->check(within(0, 10000.0, "um"));
  sim_cmd->add_option("--instrument-rotation-deg", s->yaw_deg, "The instrument's frame turned about z (deg)")
      ->capture_default_str()
      ->check(within(-360.0, 360.0, "deg"));
  sim_cmd->add_option("--instrument-tilt-deg", s->tilt_deg, "… and tilted about x (deg; needs --z)")
      ->capture_default_str()
      ->check(within(-90.0, 90.0, "deg"));
  sim_cmd->add_option("--instrument-shift-mm", s->shift_mm, "The robot's origin in the instrument's frame: X Y Z (mm)")
      ->expected(3)
      ->capture_default_str()
      ->check(within(-1e4, 1e4, "mm"));
  sim_cmd->add_flag("--z", s->spatial, "Write z_mm as well (a 3-D instrument)");
  sim_cmd->add_option("--readings", s->readings, "Readings per pose")->capture_default_str()->check(within(1, 100, ""));
  sim_cmd->add_option("--seed", s->seed, "Random seed")->capture_default_str();
  sim_cmd->callback([s] { simulate(*s); });
}

}  // namespace stiffpath::cli
