// `stiffpath mechanism show|list`: print a preset or a user's mechanism file.
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/mechanism_spec.hpp"

namespace stiffpath::cli {

namespace {
struct MechanismOptions {
  std::string which = "oc-gu";
  bool json = false;
};

void show(const MechanismOptions& o) {
  const auto spec = kinematics::load_mechanism(o.which);
  if (o.json) {
    print_json(kinematics::to_json(spec));
    return;
  }
  fmt::print("{} ({}): {}\n", spec.name, spec.source, spec.description);
  fmt::print("  build                {}\n", spec.build);
  fmt::print("  link length          {:.3f} mm (all four links)\n", units::m_to_mm(spec.link_length_m));
  fmt::print("  moving mass          {:.3f} kg\n", spec.moving_mass_kg);
  fmt::print("  centre of gravity    {} at {:.1f} mm above G\n", spec.cg_label, units::m_to_mm(spec.cg_height_m));
  fmt::print("  measurement replica  |UG| = {:.1f} mm, |UL| = {:.1f} mm\n", units::m_to_mm(spec.ug_m),
             units::m_to_mm(spec.ul_m));
  for (const auto& j : spec.joints) {
    fmt::print("  joint {:<7}        [{:.1f}, {:.1f}] deg, |w| <= {:.1f} rad/s, |a| <= {:.0f} rad/s^2\n", j.name,
               units::rad_to_deg(j.min_rad), units::rad_to_deg(j.max_rad), j.max_velocity_rad_s,
               j.max_acceleration_rad_s2);
  }
  fmt::print("  singularity margin   {:.1f} mm, condition number <= {:.1f}\n",
             units::m_to_mm(spec.margin.min_distance_m), spec.margin.max_condition_number);
  fmt::print("  compliance data      {}\n", spec.compliance_dataset);
}
}  // namespace

void add_mechanism_command(CLI::App& app) {
  auto* mech = app.add_subcommand("mechanism", "Robot presets and mechanism files");
  mech->require_subcommand(1);
  auto opts = std::make_shared<MechanismOptions>();
  auto* show_cmd = mech->add_subcommand("show", "Print a preset (oc-gu, oc-gl, sc-gu, sc-gl) or a JSON file");
  show_cmd->add_option("mechanism", opts->which, "Preset name or JSON file")->capture_default_str();
  show_cmd->add_flag("--json", opts->json, "Print the mechanism as JSON (the file format)");
  show_cmd->callback([opts] { show(*opts); });
  auto* list_cmd = mech->add_subcommand("list", "List the built-in presets");
  list_cmd->callback([] {
    for (const auto& name : kinematics::preset_names()) {
      fmt::print("{:<6} {}\n", name, kinematics::load_mechanism(name).description);
    }
  });
}

}  // namespace stiffpath::cli
