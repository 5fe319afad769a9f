// `stiffpath plot compliance|cv|run|mark|results`: figures with gnuplot (SVG, PNG and the kept script).
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "joint_robot.hpp"
#include "progress.hpp"
#include "robot_flags.hpp"
#include "twin_flags.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_directory.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/report/compliance_plots.hpp"
#include "stiffpath/report/experiment_plots.hpp"
#include "stiffpath/report/mark_plots.hpp"
#include "stiffpath/report/run_plots.hpp"
#include "stiffpath/simulation/cg_lever.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::cli {

namespace {
struct PlotOptions {
  std::string robot;
  ModelFlags model;
  std::string data;  // default: the robot's table
  std::string dir = "plots";
  double margin_mm = 0.0;
  std::string style = "screen";
  std::string input, mark, source;
  double gain = 1.0, magnification = 0.0;
  std::size_t max_points = 4000;
  bool y_down = false, quiet = false, force_robot = false;
};

//! Most mark points a simulated or scanned mark may hold (20 M points: 320 MB in memory).
constexpr std::size_t kMaxMarkPoints = 20'000'000;


std::string safe_name(std::string name) {
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
  }
  return name;
}

void add_common(CLI::App* cmd, PlotOptions& o) {
  cmd->add_option("-o,--output-dir", o.dir, "Directory for the figures")->check(output_name())->capture_default_str();
  cmd->add_option("--style", o.style, "screen (colour) or paper (black and white, larger fonts)")
      ->check(CLI::IsMember({"screen", "paper"}))->capture_default_str();
}

void print_written(const std::string& dir, const std::vector<std::string>& names) {
  for (const auto& n : names) fmt::print("wrote {0}/{1}.svg, {0}/{1}.png and the script {0}/{1}.gp\n", dir, n);
}

// The laser-on planned points of a joint file: the commanded laser path.
std::vector<Eigen::Vector2d> commanded_path(const std::string& joints) {
  job::JointReader reader(joints);
  std::vector<Eigen::Vector2d> path;
  while (const auto c = reader.next()) {
    if (c->laser_on) path.push_back(c->target_m);
  }
  return path;
}

// A mark file: x_mm, y_mm by header name, in the robot frame (y up) unless y_down.
std::vector<Eigen::Vector2d> read_mark(const std::string& file, bool y_down) {
  core::CsvReader csv(file);
  const auto x = csv.column("x_mm"), y = csv.column("y_mm");
  std::vector<Eigen::Vector2d> mark;
  while (csv.next()) {
    if (mark.size() >= kMaxMarkPoints) throw Error(csv.where(), "more than 20 million mark points");
    mark.emplace_back(csv.number(x) * 1e-3, (y_down ? -1.0 : 1.0) * csv.number(y) * 1e-3);
  }
  return mark;
}

void plot_mark_command(const PlotOptions& o) {
  core::check_output_directory(o.dir);  // before the twin runs, not after
  std::vector<core::NamedPath> inputs;
  report::MarkPlotInput input;
  input.label = std::filesystem::path(o.input).filename().string();
  if (o.mark.empty()) {
    if (!o.source.empty() && o.source != "simulated") {
      throw Error(SourceLocation{o.input}, "without --mark the mark is simulated by the twin: --source " + o.source +
                                               " does not apply");
    }
    job::JointReader reader(o.input);
    const kinematics::Robot robot = robot_for_joints(o.robot, reader, o.input, o.force_robot, "plots");
    inputs = robot_inputs(robot);
    // The twin as `simulate` runs it by default: the structural C_true, the loaded servo, the CG lever.
    simulation::SimulationOptions sim;
    simulation::TrueComplianceOptions truth_options;
    apply_twin_flags(TwinFlags{}, sim, truth_options);
    sim.cg_lever = simulation::make_cg_lever(robot);
    const auto truth = simulation::make_true_compliance(robot, truth_options);
    Progress progress("plot mark: simulating", o.quiet);
    progress.update(0.0, "the twin");
    simulation::simulate([&reader] { return reader.next(); }, robot, truth, sim, [&](const simulation::Stroke& stroke) {
      if (input.mark_m.size() + stroke.marked.size() > kMaxMarkPoints) {
        throw Error(SourceLocation{o.input}, "the simulated mark has more than 20 million points: plot a shorter job");
      }
      input.commanded_m.insert(input.commanded_m.end(), stroke.commanded.begin(), stroke.commanded.end());
      input.mark_m.insert(input.mark_m.end(), stroke.marked.begin(), stroke.marked.end());
    });
    progress.finish();
    input.source = "simulated";
  } else {
    if (o.source.empty()) {
      throw Error(SourceLocation{o.mark}, "say whether this mark is simulated or measured: --source simulated|measured");
    }
    inputs = {{"--mark", o.mark}};
    input.commanded_m = commanded_path(o.input);
    input.mark_m = read_mark(o.mark, o.y_down);
    input.source = o.source;
  }
  inputs.push_back({"joints", o.input});
  const std::string name = "mark_" + safe_name(std::filesystem::path(o.input).stem().string());
  core::AtomicDirectory out(o.dir, inputs);
  const auto s = report::plot_mark(out.staging(), name, input, report::parse_style(o.style), o.magnification);
  out.commit();
  print_written(o.dir, {name});
  fmt::print("{} mark: max deviation {:.1f} µm, RMS {:.1f} µm, drawn x{:g}\n", input.source, s.max_deviation_um,
             s.rms_deviation_um, s.magnification);
}
}  // namespace

void add_plot_command(CLI::App& app) {
  auto o = std::make_shared<PlotOptions>();
  auto* plot = app.add_subcommand("plot", "Figures with gnuplot (SVG, PNG and the gnuplot script beside them)");
  plot->require_subcommand(1);

  auto* comp = plot->add_subcommand("compliance", "Largest compliance over the workspace with principal directions");
  add_robot_flag(comp, o->robot);
  add_model_flags(comp, o->model);
  comp->add_option("--margin-mm", o->margin_mm, "Also show this far outside the grid")->capture_default_str();
  add_common(comp, *o);
  comp->callback([o] {
    const auto robot = load_robot_flag(o->robot);
    const auto loaded = compliance::load_robot_model(robot, model_request(o->model));
    const std::string name =
        "compliance_" + safe_name(!o->model.model.empty() ? std::filesystem::path(o->model.model).stem().string()
                                                          : robot.name + "-" + loaded.model->description());
    auto inputs = robot_inputs(robot);
    inputs.push_back({"--model", o->model.model});
    core::AtomicDirectory out(o->dir, inputs);
    const double largest = report::plot_compliance_map(
        out.staging(), name, *loaded.model,
        fmt::format("{} ({}, {}): largest compliance", robot.name, loaded.label, loaded.model->description()),
        o->margin_mm * 1e-3, report::parse_style(o->style));
    out.commit();
    print_written(o->dir, {name});
    fmt::print("largest compliance {:.3f} µm/N\n", largest);
  });

  auto* cv = plot->add_subcommand("cv", "Measured vs predicted deflections of every model (leave-one-out)");
  cv->add_option("data", o->data, "Displacement table CSV, or 'thesis' (default: the robot's own table)");
  add_robot_flag(cv, o->robot);
  add_common(cv, *o);
  cv->callback([o] {
    const auto robot = load_robot_flag(o->robot);
    const auto table = o->data.empty() ? compliance::robot_table(robot)
                                       : measurement::load_displacement_table(table_ref(o->data)).filter(robot.compliance.rows);
    auto report = compliance::cross_validate(compliance::group_by_point(table, compliance::ForceConvention::measured),
                                             robot.geometry, table.source);
    report.rows = robot.compliance.rows;
    report.robot = robot.name;
    const std::string name = "cv_" + safe_name(robot.name);
    auto inputs = robot_inputs(robot);
    inputs.push_back({"data", o->data});
    core::AtomicDirectory out(o->dir, inputs);
    report::plot_cross_validation(out.staging(), name, report, report::parse_style(o->style));
    out.commit();
    print_written(o->dir, {name});
  });

  auto* run = plot->add_subcommand("run", "Planned vs commanded motion, force, deflection and joints over time");
  run->add_option("joints", o->input, "Joint trajectory file from `stiffpath run` (CSV or binary)")->required();
  run->add_option("--gain", o->gain, "The run's compensation gain k (predicted deflection = (p - p_cmd)/k)")
      ->check(CLI::PositiveNumber)->check(within(0.0, 10.0, ""))->capture_default_str();
  run->add_option("--max-points", o->max_points, "Plotted points per series (peaks kept when decimating)")
      ->check(CLI::Range(100, 100000))->capture_default_str();
  add_robot_flag(run, o->robot)->description("Robot the joints were made for (default: the preset the file records, "
                                            "else oc-gu, said on stderr); its joint limits are drawn");
  run->add_flag("--force-robot", o->force_robot, "Plot a joint file written for another robot anyway");
  add_common(run, *o);
  run->callback([o] {
    const std::string name = "run_" + safe_name(std::filesystem::path(o->input).stem().string());
    const kinematics::Robot robot = [&] {
      job::JointReader reader(o->input);
      return robot_for_joints(o->robot, reader, o->input, o->force_robot, "plots");
    }();
    core::check_output_directory(o->dir);
    report::RunPlotOptions options{o->gain, o->max_points, 40, report::parse_style(o->style), &robot};
    auto inputs = robot_inputs(robot, false);
    inputs.push_back({"joints", o->input});
    core::AtomicDirectory out(o->dir, inputs);
    const auto s = report::plot_run(out.staging(), name, o->input, options);
    out.commit();
    print_written(o->dir, s.figures);
    fmt::print("robot {} (geometry {}, {})\n", robot.name, robot.geometry_hash().substr(0, 12), robot.source());
    fmt::print("{} samples over {:.4f} s ({} plotted): peak speed {:.1f} mm/s, acceleration {:.2f} m/s², jerk {:.0f} "
               "m/s³, force {:.1f} N, correction {:.1f} µm; laser on {:.4f} s at up to {:.0f} % power\n",
               s.samples, s.duration_s, s.plotted, s.peak_speed_mm_s, s.peak_acceleration_m_s2, s.peak_jerk_m_s3,
               s.peak_force_N, s.peak_correction_um, s.laser_on_s, s.peak_power * 100.0);
  });

  auto* mark = plot->add_subcommand("mark", "A simulated or scanned mark over the commanded path, deviation magnified");
  mark->add_option("joints", o->input, "Joint trajectory file: its laser-on planned points are the commanded path")
      ->required();
  mark->add_option("--mark", o->mark, "Mark CSV (x_mm, y_mm, robot frame); without it the twin simulates the mark");
  mark->add_option("--source", o->source, "What the --mark file is: simulated or measured")
      ->check(CLI::IsMember({"simulated", "measured"}));
  mark->add_flag("--y-down", o->y_down, "The mark's y axis points down (simulate --marks-csv, scan frames)");
  mark->add_option("--magnification", o->magnification, "Deviation drawn this many times larger (default: chosen)")
      ->check(CLI::PositiveNumber);
  add_robot_flag(mark, o->robot)->description("Robot the joints were made for (default: the preset the file records, "
                                             "else oc-gu, said on stderr); the twin simulates it");
  mark->add_flag("--force-robot", o->force_robot, "Simulate a joint file written for another robot anyway");
  mark->add_flag("--quiet", o->quiet, "No progress bar (it is shown only on a terminal anyway)");
  add_common(mark, *o);
  mark->callback([o] { plot_mark_command(*o); });

  auto* results = plot->add_subcommand("results", "A results table (experiment's or your scans') as figs. 4.9-4.11");
  results->add_option("table", o->input, "results.csv of `stiffpath experiment`, or your own (docs/figures.md)")
      ->required();
  results->add_option("--source", o->source, "simulated or measured, when the table has no source column")
      ->check(CLI::IsMember({"simulated", "measured"}));
  add_common(results, *o);
  results->callback([o] {
    const auto table = report::load_results_csv(o->input, o->source);
    core::AtomicDirectory out(o->dir, {{"table", o->input}});
    const auto figures = report::write_results_figures(out.staging(), table, report::parse_style(o->style));
    if (figures.empty()) {
      throw Error(SourceLocation{o->input}, "no rows with motion x, y or triangle: nothing to draw as figs. 4.9-4.11");
    }
    out.commit();
    print_written(o->dir, figures);
  });
}

}  // namespace stiffpath::cli
