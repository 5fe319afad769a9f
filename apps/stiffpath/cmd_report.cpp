// `stiffpath report -o DIR`: one self-contained HTML page on a robot, its data and model, a run and the twin's results.
#include <filesystem>
#include <fmt/format.h>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "joint_robot.hpp"
#include "progress.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/atomic_directory.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/sha256.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/measurement/data_check.hpp"
#include "stiffpath/report/compliance_plots.hpp"
#include "stiffpath/report/experiment_plots.hpp"
#include "stiffpath/report/html_page.hpp"
#include "stiffpath/report/run_plots.hpp"

namespace stiffpath::cli {

namespace {
struct ReportArgs {
  std::string robot;
  ModelFlags model_flags;
  std::string joints, experiment;
  double gain = 1.0;
  std::string output = "report";
  std::string style = "screen";
  bool quiet = false, force_robot = false;
};

// What the joint file says about its robot, read before anything is drawn.
struct JointsRobot {
  std::string name, geometry_hash;  // empty when the file does not record them
};

std::string sha_of(const core::DataRef& ref) { return core::sha256_hex(core::read_data(ref)); }

std::string figure(const std::filesystem::path& dir, const std::string& name, const std::string& caption) {
  return report::inline_figure(dir / (name + ".svg"), name, caption);
}

report::Section robot_section(const kinematics::Robot& robot, bool defaulted, const ReportArgs& a,
                              const compliance::LoadedModel* model, const JointsRobot& written_for) {
  std::vector<std::vector<std::string>> rows{
      {"robot", robot.name + (robot.description.empty() ? "" : " — " + robot.description) +
                    (defaulted ? " (the default robot: no --robot given and no joint file naming one)" : ""),
       ""},
      {"robot description", robot.preset ? "preset " + robot.name + " (built into stiffpath)" : robot.source(),
       robot.file.path.empty() ? "" : sha_of(robot.file)},
      {"geometry (canonical text)", "five-bar, moving mass " + fmt::format("{:g} kg, CG {} {:.1f} mm above G",
                                                                          robot.moving_mass_kg, robot.cg_label,
                                                                          robot.cg_height_m * 1e3),
       robot.geometry_hash()}};
  if (!robot.compliance.table.path.empty()) {
    rows.push_back({"compliance data", robot.compliance.table.label() +
                                           (robot.compliance.rows.empty() ? "" : " (rows " + robot.compliance.rows + ")"),
                    sha_of(robot.compliance.table)});
  }
  if (model != nullptr) {
    rows.push_back({"compliance model", model->label + " (" + model->model->description() + ", fitted to " +
                                            model->provenance.source + ")",
                    model->provenance.sha256.empty() ? "" : "data " + model->provenance.sha256});
  }
  if (!a.joints.empty()) {
    rows.push_back({"joint trajectory", a.joints, core::sha256_file_hex(a.joints)});
    const std::string hash = written_for.geometry_hash;
    const std::string verdict = hash.empty() ? "geometry not recorded"
                                : hash == robot.geometry_hash() ? "same geometry as the robot above"
                                                                : "another geometry (--force-robot)";
    rows.push_back({"joint trajectory written for",
                    (written_for.name.empty() ? std::string("robot not recorded") : "robot " + written_for.name) + ", " +
                        verdict,
                    hash});
  }
  if (!a.experiment.empty()) {
    const auto csv = (std::filesystem::path(a.experiment) / "results.csv").string();
    rows.push_back({"twin results", csv, core::sha256_file_hex(csv)});
  }
  return {"provenance", "Robot and data provenance",
          "<p>SHA-256 of every input, so that the page can be traced to the exact files.</p>\n" +
              report::html_table({"what", "which", "SHA-256"}, rows)};
}

report::Section checks_section(const kinematics::Robot& robot, const measurement::DisplacementTable& table) {
  const auto r = measurement::check_displacements(table, data_check_options(robot));
  const auto count = [](const auto& results) {
    int flagged = 0;
    for (const auto& x : results) flagged += x.flagged ? 1 : 0;
    return fmt::format("{} / {}", flagged, results.size());
  };
  std::string html = report::html_table(
      {"check", "flagged / checked"},
      {{"linearity (line fit residual beyond the cell accuracy)", count(r.linearity)},
       {"symmetry about the x axis", count(r.symmetry)},
       {"reciprocity (Maxwell–Betti)", count(r.reciprocity)},
       {"over-constrained moves less than simple", count(r.comparison)}});
  for (const auto& why : r.not_applicable) html += "<p>Does not apply to this robot: " + report::escape_html(why) + ".</p>\n";
  if (!r.skipped.empty()) html += fmt::format("<p>{} checks could not run on these data (missing cells or partners).</p>\n", r.skipped.size());
  html += "<p>The same checks in full: <code>stiffpath data check --robot NAME</code>.</p>\n";
  return {"checks", "Data checks", html};
}

report::Section model_section(const kinematics::Robot& robot, const measurement::DisplacementTable& table,
                              const compliance::LoadedModel& model, const std::filesystem::path& figs,
                              report::Style style) {
  auto cv = compliance::cross_validate(compliance::group_by_point(table, compliance::ForceConvention::measured),
                                       robot.geometry, table.source);
  cv.rows = robot.compliance.rows;
  cv.robot = robot.name;
  std::vector<std::vector<std::string>> rows;
  for (const auto& m : cv.methods) {
    rows.push_back({std::string(core::enum_name(m.method)), fmt::format("{:.1f}", m.mean_um), fmt::format("{:.1f}", m.max_um),
                    fmt::format("{:.1f}", m.interior_mean_um), std::to_string(m.predicted)});
  }
  std::string html = fmt::format("<p>Model used: <b>{}</b>. Leave-one-out cross-validation on {} (favoured: {}):</p>\n",
                                 report::escape_html(model.label), report::escape_html(table.source),
                                 report::escape_html(std::string(core::enum_name(compliance::favoured_method(cv)))));
  html += report::html_table({"method", "mean error (µm)", "max error (µm)", "interior mean (µm)", "points predicted"}, rows);
  const std::string map = "compliance_map", cvname = "cross_validation";
  report::plot_compliance_map(figs, map, *model.model,
                              fmt::format("{} ({}): largest compliance", robot.name, model.model->description()), 0.0, style);
  report::plot_cross_validation(figs, cvname, cv, style);
  html += figure(figs, map, "Largest eigenvalue of the compliance matrix over the measured rectangle, with principal "
                            "directions (stiffpath plot compliance).");
  html += figure(figs, cvname, "Measured vs predicted deflections of every method, each point held out in turn "
                               "(stiffpath plot cv).");
  return {"model", "Compliance model and cross-validation", html};
}

report::Section run_section(const ReportArgs& a, const kinematics::Robot& robot, const std::filesystem::path& figs,
                            report::Style style) {
  const auto s = report::plot_run(figs, "run", a.joints, {a.gain, 4000, 40, style, &robot});
  std::string html = report::html_table(
      {"quantity", "value"},
      {{"samples", std::to_string(s.samples)},
       {"duration", fmt::format("{:.4f} s", s.duration_s)},
       {"peak path speed (planned)", fmt::format("{:.1f} mm/s", s.peak_speed_mm_s)},
       {"peak path acceleration (planned)", fmt::format("{:.2f} m/s²", s.peak_acceleration_m_s2)},
       {"peak jerk (planned, by differences)", fmt::format("{:.0f} m/s³", s.peak_jerk_m_s3)},
       {"peak D'Alembert force", fmt::format("{:.1f} N", s.peak_force_N)},
       {"peak correction |p_cmd − p|", fmt::format("{:.1f} µm", s.peak_correction_um)},
       {"laser on", fmt::format("{:.4f} s, up to {:.0f} % power", s.laser_on_s, s.peak_power * 100.0)}});
  html += figure(figs, "run_motion", "Planned and commanded motion, force, predicted deflection and correction, "
                                     "laser power (stiffpath plot run).");
  html += figure(figs, "run_joints", "Joint angles, velocities and accelerations with the robot's limits dashed.");
  return {"run", "The run", html};
}

report::Section twin_section(const ReportArgs& a, const std::filesystem::path& figs, report::Style style) {
  const std::filesystem::path dir(a.experiment);
  const auto table = report::load_results_csv((dir / "results.csv").string());
  std::string html = fmt::format("<p>{} runs, {} (stiffpath experiment).</p>\n", table.rows.size(),
                                 table.source == "simulated" ? "simulated on the digital twin" : "measured");
  if (std::filesystem::exists(dir / "summary.md")) {
    html += report::markdown_html(core::read_data(core::parse_data_ref((dir / "summary.md").string())));
  }
  for (const auto& name : report::write_results_figures(figs, table, style)) {
    html += figure(figs, name, "Length or deviation area against acceleration, in the layout of the thesis's figs. "
                               "4.9–4.11 (stiffpath plot results).");
  }
  return {"twin", table.source == "simulated" ? "Digital twin results" : "Measured results", html};
}

void make_report(const ReportArgs& a) {
  const auto style = report::parse_style(a.style);
  // Every input is read and checked before anything is written: the robot (the joint file's, checked
  // against --robot), the model, the experiment's table; then the output directory.
  kinematics::Robot robot;
  JointsRobot written_for;
  bool defaulted = false;
  if (!a.joints.empty()) {
    job::JointReader reader(a.joints);
    written_for = {reader.mechanism(), reader.geometry_hash()};
    defaulted = a.robot.empty() && written_for.name.empty();
    robot = robot_for_joints(a.robot, reader, a.joints, a.force_robot, "reports");
  } else {
    defaulted = a.robot.empty();
    robot = load_robot_flag(a.robot);
    if (defaulted) fmt::print(stderr, "report: no --robot given; reporting on the default robot '{}'\n", robot.name);
  }
  if (!a.experiment.empty()) (void)report::load_results_csv((std::filesystem::path(a.experiment) / "results.csv").string());
  core::check_output_directory(a.output);
  const std::filesystem::path dir(a.output);
  Progress progress("report", a.quiet);
  std::vector<report::Section> sections;
  const bool has_data = !robot.compliance.table.path.empty();
  std::unique_ptr<compliance::LoadedModel> model;
  if (has_data || !robot.compliance.model.path.empty() || !a.model_flags.model.empty()) {
    model = std::make_unique<compliance::LoadedModel>(compliance::load_robot_model(robot, model_request(a.model_flags)));
  }
  auto inputs = robot_inputs(robot);
  inputs.push_back({"--model", a.model_flags.model});
  inputs.push_back({"--joints", a.joints});
  if (!a.experiment.empty()) {
    inputs.push_back({"--experiment", std::filesystem::path(a.experiment) / "results.csv"});
    inputs.push_back({"--experiment", std::filesystem::path(a.experiment) / "summary.md"});
  }
  core::AtomicDirectory out(dir, inputs);  // all or nothing: a full disk leaves no half
  const std::filesystem::path figs = out.staging() / "figures";
  std::filesystem::create_directory(figs);
  sections.push_back(robot_section(robot, defaulted, a, model.get(), written_for));
  progress.update(0.1, "data checks");
  if (has_data) {
    const auto table = compliance::robot_table(robot);
    sections.push_back(checks_section(robot, table));
    progress.update(0.2, "cross-validation");
    if (model) sections.push_back(model_section(robot, table, *model, figs, style));
  }
  progress.update(0.6, "run");
  if (!a.joints.empty()) sections.push_back(run_section(a, robot, figs, style));
  progress.update(0.8, "twin");
  if (!a.experiment.empty()) sections.push_back(twin_section(a, figs, style));
  progress.finish();
  const std::string subtitle = fmt::format("stiffpath {} · robot {} (geometry {}){}{}", STIFFPATH_VERSION, robot.name,
                                           robot.geometry_hash().substr(0, 12),
                                           a.joints.empty() ? "" : " · run " + a.joints,
                                           a.experiment.empty() ? "" : " · twin results " + a.experiment);
  const std::string page = report::html_page("stiffpath report: " + robot.name, subtitle, sections);
  core::write_file_atomically(out.staging() / "report.html", page);
  out.commit();
  fmt::print("wrote {} ({} sections, {:.0f} kB, figures also in {})\n", (dir / "report.html").string(),
             sections.size(), static_cast<double>(page.size()) / 1024.0, (dir / "figures").string());
}
}  // namespace

void add_report_command(CLI::App& app) {
  auto a = std::make_shared<ReportArgs>();
  auto* cmd = app.add_subcommand("report", "One self-contained HTML page: provenance, data checks, model, run, twin");
  add_robot_flag(cmd, a->robot);
  add_model_flags(cmd, a->model_flags);
  cmd->add_option("--joints", a->joints, "A joint trajectory from `stiffpath run` to show (CSV or binary); the report "
                                         "is on the robot it records unless --robot");
  cmd->add_flag("--force-robot", a->force_robot, "Report a joint file written for another robot anyway");
  cmd->add_option("--gain", a->gain, "That run's compensation gain")->check(CLI::PositiveNumber)->check(within(0.0, 10.0, ""))
      ->capture_default_str();
  cmd->add_option("--experiment", a->experiment, "An output directory of `stiffpath experiment` to show");
  cmd->add_option("-o,--output", a->output, "Output directory (report.html, figures/)")->check(output_name())->capture_default_str();
  cmd->add_option("--style", a->style, "screen (colour) or paper (black and white, larger fonts)")
      ->check(CLI::IsMember({"screen", "paper"}))->capture_default_str();
  cmd->add_flag("--quiet", a->quiet, "No progress bar (it is shown only on a terminal anyway)");
  cmd->callback([a] { make_report(*a); });
}

}  // namespace stiffpath::cli
