// `stiffpath measure CAMPAIGN.csv -o table.csv`: process raw CMM readings into the tidy displacement table.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "stiffpath/core/units.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/process_campaign.hpp"

namespace stiffpath::cli {

namespace {
struct MeasureOptions {
  std::string campaign;
  std::string robot;
  std::string output;
  bool nominal_forces = false;
  std::optional<double> nominal_step_N;
  bool json = false;
};

void run(const MeasureOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  if (!robot.replica) {
    throw Error(SourceLocation{robot.file.label()},
                fmt::format("robot '{}' has no measurement replica (measurement.UG_mm, UL_mm) for eq. 2.3", robot.name));
  }
  core::check_distinct_files(robot_inputs(robot, false, {{"campaign", o.campaign}}), {{"-o", o.output}});
  const auto campaign = measurement::load_campaign(o.campaign);
  measurement::ProcessOptions p;
  p.mechanism = robot.compliance.rows;
  p.geometry = {robot.replica->ug_m, robot.replica->ul_m};
  p.force_basis = o.nominal_forces ? measurement::ForceBasis::nominal : measurement::ForceBasis::measured;
  p.nominal_step_N = o.nominal_step_N;
  const auto table = measurement::process_campaign(campaign, p);
  measurement::save_displacement_table(table, o.output);

  double max_total = 0.0, max_sd = 0.0;
  std::string max_where;
  int with_spread = 0;
  for (const auto& r : table.rows) {
    const double total = std::sqrt(*r.dx_m * *r.dx_m + *r.dy_m * *r.dy_m + *r.dz_m * *r.dz_m);
    if (total > max_total) {
      max_total = total;
      max_where = fmt::format("{} {} step {}", r.point, measurement::to_string(r.direction), r.step);
    }
    if (r.spread) {
      ++with_spread;
      max_sd = std::max({max_sd, r.spread->dx_m, r.spread->dy_m, r.spread->dz_m});
    }
  }
  const nlohmann::json summary = {
      {"campaign", o.campaign},
      {"output", o.output},
      {"robot", robot.name},
      {"robot_rows", robot.compliance.rows},
      {"ug_mm", tidy(units::m_to_mm(robot.replica->ug_m))},
      {"ul_mm", tidy(units::m_to_mm(robot.replica->ul_m))},
      {"force_basis", o.nominal_forces ? "nominal" : "measured"},
      {"nominal_forces_from", campaign.has_nominal_forces ? "the campaign's force_nominal_N"
                              : o.nominal_step_N          ? fmt::format("step x {:g} N", *o.nominal_step_N)
                                                          : std::string("the measured forces")},
      {"readings", campaign.readings.size()},
      {"rows", table.rows.size()},
      {"rows_with_spread", with_spread},
      {"max_total_displacement_mm", tidy(units::m_to_mm(max_total))},
      {"max_total_displacement_at", max_where},
      {"max_reading_sd_um", tidy(units::m_to_um(max_sd))}};
  if (o.json) {
    print_json(summary);
    return;
  }
  fmt::print("{} readings -> {} rows ({} {}, G = U + {:.0f}/{:.0f} UL, forces {})\n", campaign.readings.size(),
             table.rows.size(), robot.name, robot.compliance.rows, units::m_to_mm(robot.replica->ug_m),
             units::m_to_mm(robot.replica->ul_m),
             !o.nominal_forces                ? std::string("measured, relative to step 0")
             : campaign.has_nominal_forces    ? std::string("nominal, from the campaign's force_nominal_N")
                                              : fmt::format("nominal, step x {:g} N", *o.nominal_step_N));
  fmt::print("largest total displacement {:.4f} mm at {}\n", units::m_to_mm(max_total), max_where);
  if (with_spread > 0) {
    fmt::print("{} rows averaged repeated readings; largest reading SD {:.1f} um\n", with_spread,
               units::m_to_um(max_sd));
  }
  fmt::print("wrote {}\n", o.output);
}
}  // namespace

void add_measure_command(CLI::App& app) {
  auto opts = std::make_shared<MeasureOptions>();
  auto* cmd = app.add_subcommand("measure", "Process a raw CMM campaign (U, L readings) into a displacement table");
  cmd->add_option("campaign", opts->campaign, "Campaign CSV (see docs/measurement.md)")->required();
  add_robot_flag(cmd, opts->robot)->description("Robot: |UG|, |UL| of its replica and its rows label (default: oc-gu)");
  cmd->add_option("-o,--output", opts->output, "Displacement table CSV to write")->check(output_name())->required();
  cmd->add_flag("--nominal-forces", opts->nominal_forces,
                "Write F_N as the campaign's nominal loads (its force_nominal_N column, or step x --nominal-step-N), "
                "not the measured ones; refused when the campaign names none");
  cmd->add_option("--nominal-step-N", opts->nominal_step_N,
                  "Nominal load per step (N) for a campaign without a force_nominal_N column")
      ->check(within(0.001, 100000.0, "N"));
  cmd->add_flag("--json", opts->json, "Print a JSON summary");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace stiffpath::cli
