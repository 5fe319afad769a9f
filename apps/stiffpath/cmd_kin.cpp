// `stiffpath kin fk|ik|grid`: the robot's kinematics at the command line (eqs. 2.1–2.2 for the thesis robot).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <vector>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::cli {

namespace {
using kinematics::Vec2;

struct KinOptions {
  std::string robot;
  double theta1_deg = 0.0, theta2_deg = 0.0;
  double x_mm = 0.0, y_mm = 0.0;
  bool json = false;
};

nlohmann::json pose_json(const kinematics::FiveBar& robot, const Vec2& q, const Vec2& p) {
  const auto passive = robot.passive_angles(q);
  const std::string why = robot.explain(p);
  return {{"x_mm", tidy(units::m_to_mm(p.x()))},
          {"y_mm", tidy(units::m_to_mm(p.y()))},
          {"theta1_rad", tidy(q.x())},
          {"theta2_rad", tidy(q.y())},
          {"theta3_rad", tidy(passive.theta3_rad)},
          {"theta4_rad", tidy(passive.theta4_rad)},
          {"condition_number", tidy(robot.condition_number(q))},
          {"reach", why.empty() ? "reachable" : why}};
}

void print_pose(const nlohmann::json& pose) {
  fmt::print("x = {:.6f} mm, y = {:.6f} mm\n", pose["x_mm"].get<double>(), pose["y_mm"].get<double>());
  fmt::print("theta1 = {:.9f} rad ({:.6f} deg), theta2 = {:.9f} rad ({:.6f} deg)\n", pose["theta1_rad"].get<double>(),
             units::rad_to_deg(pose["theta1_rad"].get<double>()), pose["theta2_rad"].get<double>(),
             units::rad_to_deg(pose["theta2_rad"].get<double>()));
  fmt::print("passive (distal links): theta3 = {:.9f} rad, theta4 = {:.9f} rad\n", pose["theta3_rad"].get<double>(),
             pose["theta4_rad"].get<double>());
  fmt::print("condition number = {:.4f} ({})\n", pose["condition_number"].get<double>(),
             pose["reach"].get<std::string>());
}

void run_fk(const KinOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  const Vec2 q{units::deg_to_rad(o.theta1_deg), units::deg_to_rad(o.theta2_deg)};
  const Vec2 p = robot.forward(q);
  const auto five_bar = robot.five_bar();
  auto pose = pose_json(five_bar, q, p);
  // Angles whose elbows sit on the other side than the robot's working mode give a point the robot
  // reaches with other angles: say so rather than call the pose reachable.
  const auto back = five_bar.solve_inverse(p);
  if (back.status == kinematics::Reach::ok &&
      (std::abs(std::remainder(back.q.x() - q.x(), 2 * M_PI)) > 1e-9 ||
       std::abs(std::remainder(back.q.y() - q.y(), 2 * M_PI)) > 1e-9)) {
    pose["reach"] = fmt::format("these angles put the elbows out of the robot's working mode (elbows [{:+d}, {:+d}])",
                                robot.geometry.elbows[0], robot.geometry.elbows[1]);
  }
  o.json ? print_json(pose) : print_pose(pose);
}

void run_ik(const KinOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  const Vec2 p{units::mm_to_m(o.x_mm), units::mm_to_m(o.y_mm)};
  const auto pose = pose_json(robot.five_bar(), robot.inverse(p), p);
  o.json ? print_json(pose) : print_pose(pose);
}

// The robot's measurement points (its table's rows) through inverse kinematics.
void run_grid(const KinOptions& o) {
  const auto robot = load_robot_flag(o.robot);
  const auto five_bar = robot.five_bar();
  const auto table = compliance::robot_table(robot);
  nlohmann::json points = nlohmann::json::array();
  if (!o.json) fmt::print("{:>6} {:>10} {:>8} {:>12} {:>12} {:>8} {:>10}\n", "point", "x_mm", "y_mm", "theta1_deg",
                          "theta2_deg", "cond", "fk_err_nm");
  std::vector<std::string> seen;
  for (const auto& row : table.rows) {
    if (std::find(seen.begin(), seen.end(), row.point) != seen.end()) continue;
    seen.push_back(row.point);
    const Vec2 p{row.x_m, row.y_m};
    const Vec2 q = robot.inverse(p);
    const double err_nm = (five_bar.forward(q) - p).norm() * 1e9;
    auto pose = pose_json(five_bar, q, p);
    pose["point"] = row.point;
    pose["fk_roundtrip_error_nm"] = tidy(err_nm);
    points.push_back(pose);
    if (!o.json) {
      fmt::print("{:>6} {:>10.3f} {:>8.1f} {:>12.6f} {:>12.6f} {:>8.4f} {:>10.2e}\n", row.point,
                 units::m_to_mm(row.x_m), units::m_to_mm(row.y_m), units::rad_to_deg(q.x()), units::rad_to_deg(q.y()),
                 five_bar.condition_number(q), err_nm);
    }
  }
  if (o.json) print_json({{"robot", robot.name}, {"points", points}});
}
}  // namespace

void add_kin_command(CLI::App& app) {
  auto* kin = app.add_subcommand("kin", "Five-bar kinematics of a robot (thesis eqs. 2.1-2.2 for its own)");
  kin->require_subcommand(1);
  auto opts = std::make_shared<KinOptions>();

  auto* fk = kin->add_subcommand("fk", "Forward kinematics: joint angles -> platform point");
  fk->add_option("--theta1-deg", opts->theta1_deg, "Left actuator's angle (deg)")->required()->check(within(-1e4, 1e4, "deg"));
  fk->add_option("--theta2-deg", opts->theta2_deg, "Right actuator's angle (deg)")->required()->check(within(-1e4, 1e4, "deg"));
  auto* ik = kin->add_subcommand("ik", "Inverse kinematics: platform point -> joint angles (reach and joint limits checked)");
  ik->add_option("--x-mm", opts->x_mm, "Platform x (mm)")->required()->check(within(-1e4, 1e4, "mm"));
  ik->add_option("--y-mm", opts->y_mm, "Platform y (mm)")->required()->check(within(-1e4, 1e4, "mm"));
  auto* grid = kin->add_subcommand("grid", "Inverse kinematics on the robot's measurement points (its table)");
  for (auto* sub : {fk, ik, grid}) {
    add_robot_flag(sub, opts->robot);
    sub->add_flag("--json", opts->json, "Print one JSON object with units in its keys");
  }
  fk->callback([opts] { run_fk(*opts); });
  ik->callback([opts] { run_ik(*opts); });
  grid->callback([opts] { run_grid(*opts); });
}

}  // namespace stiffpath::cli
