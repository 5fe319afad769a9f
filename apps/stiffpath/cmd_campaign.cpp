// `stiffpath campaign simulate`: a virtual CMM campaign (known displacements → noisy U, L readings).
#include <fmt/format.h>

#include <memory>
#include <set>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"

namespace stiffpath::cli {

namespace {
struct SimulateOptions {
  std::string robot;
  std::string truth;  // default: the robot's table
  bool linearize = false;
  int readings = 1;
  double noise_sigma_um = 11.5;
  std::uint64_t seed = 1;
  double g_height_mm = 0.0;
  std::string output;
  std::string truth_output;
  bool json = false;
};

void run(const SimulateOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  if (!robot.replica) {
    throw Error(SourceLocation{robot.file.label()},
                fmt::format("robot '{}' has no measurement replica (measurement.UG_mm, UL_mm): a CMM campaign reads U "
                            "and L on it",
                            robot.name));
  }
  if (o.truth.empty() && robot.compliance.table.empty()) {
    throw Error(fmt::format("robot '{}' names no displacement table: give the truth with --truth", robot.name));
  }
  auto table = measurement::load_displacement_table(o.truth.empty() ? robot.compliance.table : table_ref(o.truth));
  if (table.mechanisms().size() > 1) table = table.filter(robot.compliance.rows);
  if (table.rows.empty()) {
    throw Error(SourceLocation{table.source},
                "no rows with mechanism '" + robot.compliance.rows + "' (robot " + robot.name + ")");
  }
  // A table with gaps (the thesis's garbled cells) is replaced by its per-point linear fit; quantities
  // the table lacks entirely (dz, rx, ry are optional) become zero.
  const bool gaps = measurement::has_gaps(table);
  if (o.linearize || gaps) {
    table = measurement::linear_truth(table);
  } else {
    table = measurement::zero_absent_quantities(table);
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
                {"noise_sigma_um", o.noise_sigma_um},
                {"seed", o.seed}});
    return;
  }
  std::set<std::pair<std::string, int>> series;
  for (const auto& r : table.rows) series.emplace(r.point, static_cast<int>(r.direction));
  fmt::print("{} readings of robot {}: {} series (truth: {}{}), noise sigma {:.1f} um, seed {}\nwrote {}\n",
             campaign.readings.size(), robot.name, series.size(), table.source,
             o.linearize || gaps ? ", linear fit per point" : "", o.noise_sigma_um, o.seed, o.output);
}
}  // namespace

void add_campaign_command(CLI::App& app) {
  auto* campaign = app.add_subcommand("campaign", "CMM measurement campaigns");
  campaign->require_subcommand(1);
  auto opts = std::make_shared<SimulateOptions>();
  auto* sim = campaign->add_subcommand("simulate", "Write a virtual campaign: truth displacements -> noisy U, L readings");
  add_robot_flag(sim, opts->robot);
  sim->add_option("--truth", opts->truth, "Displacement table giving the true displacements, or 'thesis' "
                                          "(default: the robot's own table)");
  sim->add_flag("--linearize", opts->linearize, "Replace the truth by its per-point linear fit (fills gaps)");
  sim->add_option("--readings", opts->readings, "Readings per load step")->capture_default_str()
      ->check(within(1, 1000, ""));
  sim->add_option("--noise-sigma-um", opts->noise_sigma_um, "Sigma of each U, L coordinate (um); 11.5 = +-23 um at 2 sigma")
      ->capture_default_str()
      ->check(within(0, 10000.0, "um"));
  sim->add_option("--seed", opts->seed, "Random seed")->capture_default_str();
  sim->add_option("--g-height-mm", opts->g_height_mm, "z of G at step 0 in the CMM frame (mm)")->capture_default_str()
      ->check(within(-10000.0, 10000.0, "mm"));
  sim->add_option("-o,--output", opts->output, "Campaign CSV to write")->required();
  sim->add_option("--truth-output", opts->truth_output, "Also write the truth as a displacement table");
  sim->add_flag("--json", opts->json, "Print a JSON summary");
  sim->callback([opts] { run(*opts); });
}

}  // namespace stiffpath::cli
