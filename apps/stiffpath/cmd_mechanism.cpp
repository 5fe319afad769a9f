// `stiffpath robot show|list` (alias `mechanism`): print a preset or a user's robot file.
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/robot_json.hpp"

namespace stiffpath::cli {

namespace {
struct RobotOptions {
  std::string which = kDefaultRobot;
  bool json = false;
};

std::string mm(const kinematics::Vec2& p) {
  return fmt::format("({:.3f}, {:.3f}) mm", units::m_to_mm(p.x()), units::m_to_mm(p.y()));
}

void show(const RobotOptions& o) {
  const auto r = kinematics::load_robot(o.which);
  if (o.json) {
    print_json(kinematics::to_json(r));
    return;
  }
  const auto& g = r.geometry;
  fmt::print("{} ({}): {}\n", r.name, r.source(), r.description);
  fmt::print("  actuators            left {}, right {}\n", mm(g.actuator_m[0]), mm(g.actuator_m[1]));
  fmt::print("  links                left {:.3f} + {:.3f} mm, right {:.3f} + {:.3f} mm (proximal + distal)\n",
             units::m_to_mm(g.proximal_m[0]), units::m_to_mm(g.distal_m[0]), units::m_to_mm(g.proximal_m[1]),
             units::m_to_mm(g.distal_m[1]));
  fmt::print("  working mode         elbows [{:+d}, {:+d}], assembly {:+d}{}\n", g.elbows[0], g.elbows[1], g.assembly,
             g.is_thesis_case() ? " (the thesis's parallelogram five-bar: eqs. 2.1-2.2)" : "");
  if (g.joint_zero_rad[0] != 0.0 || g.joint_zero_rad[1] != 0.0) {
    fmt::print("  joint zero offsets   theta1 {:+.4f} deg, theta2 {:+.4f} deg (link angle = joint reading + offset)\n",
               units::rad_to_deg(g.joint_zero_rad[0]), units::rad_to_deg(g.joint_zero_rad[1]));
  }
  fmt::print("  geometry sha256      {}\n", r.geometry_hash());
  fmt::print("  moving mass          {:.3f} kg\n", r.moving_mass_kg);
  fmt::print("  centre of gravity    {} at {:.1f} mm above G\n", r.cg_label, units::m_to_mm(r.cg_height_m));
  if (r.replica) {
    fmt::print("  measurement replica  |UG| = {:.1f} mm, |UL| = {:.1f} mm\n", units::m_to_mm(r.replica->ug_m),
               units::m_to_mm(r.replica->ul_m));
  }
  for (const auto& j : r.joints) {
    fmt::print("  joint {:<7}        [{:.1f}, {:.1f}] deg, |w| <= {:.1f} rad/s, |a| <= {:.0f} rad/s^2\n", j.name,
               units::rad_to_deg(j.min_rad), units::rad_to_deg(j.max_rad), j.max_velocity_rad_s,
               j.max_acceleration_rad_s2);
  }
  fmt::print("  singularity margin   {:.1f} mm, condition number <= {:.1f}, distal links >= {:.1f} deg from collinear\n",
             units::m_to_mm(r.margin.min_distance_m), r.margin.max_condition_number,
             units::rad_to_deg(r.margin.min_distal_angle_rad));
  if (r.home_m) fmt::print("  home                 {}\n", mm(*r.home_m));
  const auto& c = r.compliance;
  fmt::print("  compliance table     {}{}\n", c.table.empty() ? "(none)" : c.table.label(),
             c.rows.empty() ? "" : ", rows " + c.rows);
  fmt::print("  compliance model     {}\n", !c.model.empty()      ? c.model.label()
                                          : c.method             ? std::string(core::enum_name(*c.method)) + " fitted to the table"
                                          : c.table.empty()      ? "(none)"
                                                                 : "fitted to the table by the method cross-validation favours");
}
}  // namespace

void add_mechanism_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("robot", "Robot presets and robot files");
  cmd->alias("mechanism");
  cmd->require_subcommand(1);
  auto opts = std::make_shared<RobotOptions>();
  auto* show_cmd = cmd->add_subcommand("show", "Print a preset (oc-gu, oc-gl, sc-gu, sc-gl) or a robot file");
  show_cmd->add_option("robot", opts->which, "Preset name or robot file")->capture_default_str();
  show_cmd->add_flag("--json", opts->json, "Print the robot as JSON: a robot file (paths resolved)");
  show_cmd->callback([opts] { show(*opts); });
  auto* list_cmd = cmd->add_subcommand("list", "List the built-in presets");
  list_cmd->callback([] {
    for (const auto& name : kinematics::preset_names()) {
      fmt::print("{:<6} {}\n", name, kinematics::load_robot(name).description);
    }
  });
}

}  // namespace stiffpath::cli
