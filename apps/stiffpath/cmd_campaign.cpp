// `stiffpath campaign plan|simulate|score`: design a CMM compliance campaign, rehearse it on a known field, score the result.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <set>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/calibration/campaign_plan.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/distinct_files.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"
#include "stiffpath/report/campaign_plots.hpp"
#include "stiffpath/simulation/structural_terms.hpp"

namespace stiffpath::cli {

namespace {
struct SimulateOptions {
  std::string robot;
  std::string truth;  // default: the robot's table
  std::string plan;   // a campaign plan: the truth is the field at its rows
  std::string field;  // a model file or built-in model: the known field
  std::string field_terms;  // or the field in the robot's own terms
  bool linearize = false;
  int readings = 1;
  double noise_sigma_um = 11.5;
  std::uint64_t seed = 1;
  double g_height_mm = 0.0;
  std::string output;
  std::string truth_output;
  bool json = false;
};

// The known field of a rehearsal: a model (file or built-in, for this robot's geometry) or the robot's own terms.
std::shared_ptr<const compliance::Model> known_field(const kinematics::Robot& robot, const std::string& field,
                                                     const std::string& terms, const compliance::GridBounds& region) {
  if (!field.empty() && !terms.empty()) throw Error("give the known field once: --field or --field-terms");
  if (field.empty() && terms.empty()) throw Error("give the known field: --field MODEL or --field-terms TERMS");
  if (!terms.empty()) return simulation::structural_model_from_terms(robot, terms, region);
  compliance::LoadedModel loaded = compliance::load_model(field);
  compliance::check_model_geometry(loaded, robot, false);
  loaded.model->set_outside_policy(compliance::OutsidePolicy::extrapolate);
  return std::shared_ptr<const compliance::Model>(std::move(loaded.model));
}

// Step 0's hanging load from the table itself: force_kgf − F_N/g of its rows (0 for a table without force_kgf).
double step0_kgf_of(const measurement::DisplacementTable& table) {
  double sum = 0.0;
  for (const auto& r : table.rows) sum += r.force_kgf - r.force_N / units::standard_gravity_m_s2;
  return table.rows.empty() ? 0.0 : std::max(0.0, sum / static_cast<double>(table.rows.size()));
}

void run(const SimulateOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  if (!robot.replica) {
    throw Error(SourceLocation{robot.file.label()},
                fmt::format("robot '{}' has no measurement replica (measurement.UG_mm, UL_mm): a CMM campaign reads U "
                            "and L on it",
                            robot.name));
  }
  measurement::DisplacementTable table;
  bool gaps = false;
  if (!o.plan.empty()) {
    if (!o.truth.empty()) throw Error("--plan and --truth both give the truth: use one");
    core::check_distinct_files(robot_inputs(robot, false, {{"--plan", o.plan}, {"--field", o.field}}),
                               {{"-o", o.output}, {"--truth-output", o.truth_output}});
    const auto rows = calibration::load_campaign_plan(o.plan);
    const auto field = known_field(robot, o.field, o.field_terms, compliance::table_region(rows));
    table = calibration::truth_from_field(rows, *field);
  } else {
    if (!o.field.empty() || !o.field_terms.empty()) throw Error("--field and --field-terms need --plan (the points to measure)");
    if (o.truth.empty() && robot.compliance.table.empty()) {
      throw Error(fmt::format("robot '{}' names no displacement table: give the truth with --truth, or a --plan and a "
                              "--field",
                              robot.name));
    }
    const core::DataRef truth = o.truth.empty() ? robot.compliance.table : table_ref(o.truth);
    core::check_distinct_files(robot_inputs(robot, false, {{"--truth", truth.builtin ? "" : truth.path}}),
                               {{"-o", o.output}, {"--truth-output", o.truth_output}});
    table = measurement::load_displacement_table(truth);
    if (table.mechanisms().size() > 1) table = table.filter(robot.compliance.rows);
    if (table.rows.empty()) {
      throw Error(SourceLocation{table.source},
                  "no rows with mechanism '" + robot.compliance.rows + "' (robot " + robot.name + ")");
    }
    // A table with gaps (the thesis's garbled cells) is replaced by its per-point linear fit; quantities
    // the table lacks entirely (dz, rx, ry are optional) become zero.
    gaps = measurement::has_gaps(table);
    if (o.linearize || gaps) {
      table = measurement::linear_truth(table);
    } else {
      table = measurement::zero_absent_quantities(table);
    }
  }
  measurement::VirtualCampaignOptions v;
  v.geometry = {robot.replica->ug_m, robot.replica->ul_m};
  v.readings_per_step = o.readings;
  v.noise_sigma_m = units::um_to_m(o.noise_sigma_um);
  v.seed = o.seed;
  v.g_height_m = units::mm_to_m(o.g_height_mm);
  v.step0_kgf = measurement::step0_load_kgf(table);  // the table's own step 0, no hook it does not name
  const auto campaign = measurement::simulate_campaign(table, v);
  if (!o.truth_output.empty()) measurement::save_displacement_table(table, o.truth_output);
  measurement::save_campaign(campaign, o.output);
  if (o.json) {
    print_json({{"output", o.output},
                {"truth_output", o.truth_output},
                {"truth", table.source},
                {"robot", robot.name},
                {"robot_rows", robot.compliance.rows},
                {"readings", campaign.readings.size()},
                {"readings_per_step", o.readings},
                {"step0_kgf", tidy(v.step0_kgf)},
                {"noise_sigma_um", o.noise_sigma_um},
                {"seed", o.seed}});
    return;
  }
  std::set<std::pair<std::string, int>> series;
  for (const auto& r : table.rows) series.emplace(r.point, static_cast<int>(r.direction));
  fmt::print("{} readings of robot {}: {} series (truth: {}{}), step 0 at {:.4f} kgf, noise sigma {:.1f} um, seed {}\n"
             "wrote {}\n",
             campaign.readings.size(), robot.name, series.size(), table.source,
             o.linearize || gaps ? ", linear fit per point" : "", v.step0_kgf, o.noise_sigma_um, o.seed, o.output);
}
// ---- plan ----
struct PlanOptions {
  std::string robot;
  int points = 12;
  std::vector<double> loads_N;
  int load_steps = 3;
  std::vector<std::string> directions;
  std::vector<double> region_mm;
  double step0_kgf = -1.0;  // < 0: the robot's table's
  double noise_um = 11.5;
  double max_condition = 4.0;
  std::string layout = "planned";
  std::string output;
  std::string plot_dir;
  std::string style = "screen";
  bool json = false;
};

measurement::ForceDirection direction_of(const std::string& text) {
  if (text == "+x") return measurement::ForceDirection::plus_x;
  if (text == "-x") return measurement::ForceDirection::minus_x;
  if (text == "+y") return measurement::ForceDirection::plus_y;
  if (text == "-y") return measurement::ForceDirection::minus_y;
  throw Error(fmt::format("--directions: '{}' is not a load direction (+x, -x, +y, -y)", text));
}

void plan(const PlanOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  core::check_distinct_files(robot_inputs(robot, true), {{"-o", o.output}});
  calibration::CampaignPlanSettings s;
  s.points = o.points;
  s.load_steps = o.load_steps;
  s.max_condition_number = o.max_condition;
  if (o.layout != "planned" && o.layout != "grid") throw Error("--layout: '" + o.layout + "' is neither planned nor grid");
  s.regular_grid = o.layout == "grid";
  // Loads, directions and step 0 from the robot's own table unless given.
  std::optional<measurement::DisplacementTable> table;
  if (!robot.compliance.table.empty()) table = compliance::robot_table(robot);
  if (!o.loads_N.empty()) {
    s.candidate_loads_N = o.loads_N;
  } else if (table) {
    for (const auto& r : table->rows) s.candidate_loads_N.push_back(r.force_N);
  } else {
    throw Error(fmt::format("robot '{}' has no compliance table to take the load steps from: give them with --loads "
                            "(N, e.g. --loads 20 40 60 80)",
                            robot.name));
  }
  if (!o.directions.empty()) {
    s.directions.clear();
    for (const auto& d : o.directions) s.directions.push_back(direction_of(d));
  } else if (table) {
    s.directions.clear();
    for (const auto& r : table->rows) {
      if (std::find(s.directions.begin(), s.directions.end(), r.direction) == s.directions.end()) s.directions.push_back(r.direction);
    }
  }
  s.step0_kgf = o.step0_kgf >= 0.0 ? o.step0_kgf : table ? step0_kgf_of(*table) : 0.0;
  // One displacement's σ: G from U and L (eq. 2.3) at a step less G at step 0, one reading each.
  const double r = robot.replica ? robot.replica->ug_m / robot.replica->ul_m : 0.0;
  s.cell_sigma_m = units::um_to_m(o.noise_um) * std::sqrt((1 - r) * (1 - r) + r * r) * std::sqrt(2.0);
  if (!o.region_mm.empty()) {
    const auto& g = o.region_mm;
    if (!(g[1] > g[0] && g[3] > g[2])) throw Error("--region-mm: give XMIN XMAX YMIN YMAX with XMAX > XMIN and YMAX > YMIN");
    s.region = compliance::GridBounds{g[0] * 1e-3, g[1] * 1e-3, g[2] * 1e-3, g[3] * 1e-3};
  }
  if (!o.plot_dir.empty()) core::check_output_directory(o.plot_dir);
  const auto result = calibration::plan_campaign(robot, s);
  calibration::save_campaign_plan(result, o.output);
  if (!o.plot_dir.empty()) {
    core::create_output_directory(o.plot_dir);
    report::plot_campaign_plan(o.plot_dir, "campaign_plan", result, calibration::usable_lattice(robot, o.max_condition),
                               calibration::campaign_map(robot, result, s.cell_sigma_m),
                               fmt::format("robot {}: {} points, loads {} N", robot.name, result.points.size(),
                                           fmt::join(result.loads_N, ", ")),
                               report::parse_style(o.style));
  }
  const auto& g = result.region;
  std::vector<std::string> dirs;
  for (const auto d : result.directions) dirs.emplace_back(measurement::to_string(d));
  if (o.json) {
    nlohmann::json pts = nlohmann::json::array();
    for (const auto& p : result.points) pts.push_back({tidy(p.x() * 1e3), tidy(p.y() * 1e3)});
    print_json({{"robot", robot.name}, {"output", o.output}, {"points_mm", pts},
                {"region_mm", {tidy(g.x_min * 1e3), tidy(g.x_max * 1e3), tidy(g.y_min * 1e3), tidy(g.y_max * 1e3)}},
                {"loads_N", result.loads_N}, {"directions", dirs}, {"step0_kgf", tidy(result.step0_kgf)},
                {"cell_sigma_um", tidy(s.cell_sigma_m * 1e6)},
                {"physical_variance_vs_grid", tidy(result.physical_ratio)},
                {"interpolation_variance_vs_grid", tidy(result.interpolation_ratio)},
                {"grid", {result.grid_nx, result.grid_ny}}});
    return;
  }
  fmt::print("{} points for robot {} over x [{:.1f}, {:.1f}] mm, y [{:.1f}, {:.1f}] mm; loads {} N along {}, step 0 at "
             "{:.4f} kgf\n",
             result.points.size(), robot.name, g.x_min * 1e3, g.x_max * 1e3, g.y_min * 1e3, g.y_max * 1e3,
             fmt::join(result.loads_N, ", "), fmt::join(dirs, " and "), result.step0_kgf);
  fmt::print("against a regular {} x {} grid: the physical model's mean prediction variance x{:.2f}, the residual "
             "spline's mean interpolation variance x{:.2f} (one displacement's sigma {:.1f} um)\nwrote {}{}\n",
             result.grid_nx, result.grid_ny, result.physical_ratio, result.interpolation_ratio, s.cell_sigma_m * 1e6,
             o.output, o.plot_dir.empty() ? "" : " and " + (std::filesystem::path(o.plot_dir) / "campaign_plan.svg").string());
}

// ---- score ----
struct ScoreOptions {
  std::string robot;
  ModelFlags request;
  std::string field;
  std::string field_terms;
  double force_N = 0.0;
  bool json = false;
};

void score(const ScoreOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  auto loaded = compliance::load_robot_model(robot, model_request(o.request));
  const compliance::GridBounds b = loaded.model->bounds();
  const auto field = known_field(robot, o.field, o.field_terms, b);
  constexpr int kLattice = 41;
  double sum = 0.0, worst = 0.0;
  for (int i = 0; i < kLattice; ++i) {
    for (int j = 0; j < kLattice; ++j) {
      const compliance::Vec2 p(b.x_min + (b.x_max - b.x_min) * i / (kLattice - 1.0), b.y_min + (b.y_max - b.y_min) * j / (kLattice - 1.0));
      const double e = (loaded.model->compliance(p) - field->compliance(p)).norm() * o.force_N;
      sum += e * e;
      worst = std::max(worst, e);
    }
  }
  const double rms = std::sqrt(sum / (kLattice * kLattice));
  if (o.json) {
    print_json({{"robot", robot.name}, {"model", loaded.label}, {"force_N", o.force_N}, {"rms_um", tidy(rms * 1e6)},
                {"max_um", tidy(worst * 1e6)}, {"lattice", kLattice}});
    return;
  }
  fmt::print("{} against the known field over its measured region ({} x {} lattice), |C_model - C_field|_F x {:g} N: "
             "RMS {:.1f} um, largest {:.1f} um\n",
             loaded.label, kLattice, kLattice, o.force_N, rms * 1e6, worst * 1e6);
}
}  // namespace

void add_campaign_command(CLI::App& app) {
  auto* campaign = app.add_subcommand("campaign", "CMM measurement campaigns: plan, rehearse, score");
  campaign->require_subcommand(1);
  auto opts = std::make_shared<SimulateOptions>();
  auto* sim = campaign->add_subcommand("simulate", "Write a virtual campaign: truth displacements -> noisy U, L readings");
  add_robot_flag(sim, opts->robot);
  sim->add_option("--truth", opts->truth, "Displacement table giving the true displacements, or 'thesis' "
                                          "(default: the robot's own table)");
  sim->add_option("--plan", opts->plan, "A campaign plan (campaign plan -o): measure the known field at its rows");
  sim->add_option("--field", opts->field, "With --plan: the known field, a compliance model file or built-in model");
  sim->add_option("--field-terms", opts->field_terms,
                  "With --plan: the known field in the robot's own terms, e.g. "
                  "'actuator_rad_per_Nm=2e-5/3e-5,distal_axial_m_per_N=5e-8,base_x_m_per_N=1e-8'");
  sim->add_flag("--linearize", opts->linearize, "Replace the truth by its per-point linear fit (fills gaps)");
  sim->add_option("--readings", opts->readings, "Readings per load step")->capture_default_str()
      ->check(within(1, 1000, ""));
  sim->add_option("--noise-sigma-um", opts->noise_sigma_um, "Sigma of each U, L coordinate (um); 11.5 = +-23 um at 2 sigma")
      ->capture_default_str()
      ->check(within(0, 10000.0, "um"));
  sim->add_option("--seed", opts->seed, "Random seed")->capture_default_str();
  sim->add_option("--g-height-mm", opts->g_height_mm, "z of G at step 0 in the CMM frame (mm)")->capture_default_str()
      ->check(within(-10000.0, 10000.0, "mm"));
  sim->add_option("-o,--output", opts->output, "Campaign CSV to write")->check(output_name())->required();
  sim->add_option("--truth-output", opts->truth_output, "Also write the truth as a displacement table")->check(output_name());
  sim->add_flag("--json", opts->json, "Print a JSON summary");
  sim->callback([opts] { run(*opts); });

  auto p = std::make_shared<PlanOptions>();
  auto* plan_cmd = campaign->add_subcommand("plan", "Choose the points and load steps the physical model learns most from");
  add_robot_flag(plan_cmd, p->robot);
  plan_cmd->add_option("--points", p->points, "Measurement points")->capture_default_str()->check(within(4, calibration::kMaxCampaignPoints, ""));
  plan_cmd->add_option("--loads", p->loads_N, "Available loads (N, relative to step 0); default: the robot's table's")
      ->check(within(0.001, 1e5, "N"));
  plan_cmd->add_option("--load-steps", p->load_steps, "Loaded steps per series, chosen from the loads")->capture_default_str()->check(within(2, 20, ""));
  plan_cmd->add_option("--directions", p->directions, "Load directions (+x, -x, +y, -y); default: the robot's table's, else +x +y");
  plan_cmd->add_option("--region-mm", p->region_mm, "The region to model: XMIN XMAX YMIN YMAX (default: the largest usable rectangle)")
      ->expected(4)
      ->check(within(-1e4, 1e4, "mm"));
  plan_cmd->add_option("--step0-kgf", p->step0_kgf, "Step 0's hanging load (kgf; default: the robot's table's, else 0)")
      ->check(within(0.0, 1e4, "kgf"));
  plan_cmd->add_option("--noise-um", p->noise_um, "Sigma of one instrument coordinate (um)")->capture_default_str()->check(within(0.01, 1e4, "um"));
  plan_cmd->add_option("--max-condition", p->max_condition, "The default region keeps J's condition number below this")
      ->capture_default_str()
      ->check(within(1.01, 1e3, ""));
  plan_cmd->add_option("--layout", p->layout, "planned (chosen points) or grid (the regular grid of about as many, to compare)")
      ->capture_default_str();
  plan_cmd->add_option("-o,--output", p->output, "Plan CSV to write (point,x_mm,y_mm,direction,step,force_kgf,F_N)")->required();
  plan_cmd->add_option("--plot-dir", p->plot_dir, "Also draw the usable region, the points and the predicted uncertainty here");
  plan_cmd->add_option("--style", p->style, "Figure style: screen or paper")->capture_default_str();
  plan_cmd->add_flag("--json", p->json, "Print a JSON summary");
  plan_cmd->callback([p] { plan(*p); });

  auto sc = std::make_shared<ScoreOptions>();
  auto* score_cmd = campaign->add_subcommand("score", "How well a fitted model recovers a known field over its region");
  add_robot_flag(score_cmd, sc->robot);
  add_model_flags(score_cmd, sc->request);
  score_cmd->add_option("--field", sc->field, "The known field: a compliance model file or built-in model");
  score_cmd->add_option("--field-terms", sc->field_terms, "The known field in the robot's own terms (as campaign simulate)");
  score_cmd->add_option("--force-n", sc->force_N, "The force the compliance error is multiplied by (N)")->required()->check(within(0.001, 1e6, "N"));
  score_cmd->add_flag("--json", sc->json, "Print JSON");
  score_cmd->callback([sc] { score(*sc); });
}

}  // namespace stiffpath::cli
