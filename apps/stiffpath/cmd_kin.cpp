// `stiffpath kin fk|ik|grid`: five-bar kinematics at the command line (eqs. 2.1–2.2).
#include <array>
#include <fmt/format.h>
#include <memory>

#include "commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/mechanism_spec.hpp"

namespace stiffpath::cli {

namespace {
using kinematics::Vec2;

struct KinOptions {
  std::string mechanism = "oc-gu";
  double theta1_deg = 0.0, theta2_deg = 0.0;
  double x_mm = 0.0, y_mm = 0.0;
  bool json = false;
};

nlohmann::json pose_json(const kinematics::FiveBar& robot, const Vec2& q, const Vec2& p) {
  const auto passive = kinematics::FiveBar::passive_angles(q);
  return {{"x_mm", tidy(units::m_to_mm(p.x()))},
          {"y_mm", tidy(units::m_to_mm(p.y()))},
          {"theta1_rad", tidy(q.x())},
          {"theta2_rad", tidy(q.y())},
          {"theta3_rad", tidy(passive.theta3_rad)},
          {"theta4_rad", tidy(passive.theta4_rad)},
          {"condition_number", tidy(robot.condition_number(q))},
          {"reach", kinematics::describe(robot.check_reach(p))}};
}

void print_pose(const nlohmann::json& pose) {
  fmt::print("x = {:.6f} mm, y = {:.6f} mm\n", pose["x_mm"].get<double>(), pose["y_mm"].get<double>());
  fmt::print("theta1 = {:.9f} rad ({:.6f} deg), theta2 = {:.9f} rad ({:.6f} deg)\n", pose["theta1_rad"].get<double>(),
             units::rad_to_deg(pose["theta1_rad"].get<double>()), pose["theta2_rad"].get<double>(),
             units::rad_to_deg(pose["theta2_rad"].get<double>()));
  fmt::print("passive: theta3 = {:.9f} rad, theta4 = {:.9f} rad\n", pose["theta3_rad"].get<double>(),
             pose["theta4_rad"].get<double>());
  fmt::print("condition number = {:.4f} ({})\n", pose["condition_number"].get<double>(),
             pose["reach"].get<std::string>());
}

void run_fk(const KinOptions& o) {
  const auto robot = kinematics::load_mechanism(o.mechanism).five_bar();
  const Vec2 q{units::deg_to_rad(o.theta1_deg), units::deg_to_rad(o.theta2_deg)};
  const auto pose = pose_json(robot, q, robot.forward(q));
  o.json ? print_json(pose) : print_pose(pose);
}

void run_ik(const KinOptions& o) {
  const auto robot = kinematics::load_mechanism(o.mechanism).five_bar();
  const Vec2 p{units::mm_to_m(o.x_mm), units::mm_to_m(o.y_mm)};
  const auto pose = pose_json(robot, robot.inverse(p), p);
  o.json ? print_json(pose) : print_pose(pose);
}

// The thesis's 3 × 5 measurement grid (fig. 2.5) through inverse kinematics: the demo until `run` exists.
void run_grid(const KinOptions& o) {
  const auto spec = kinematics::load_mechanism(o.mechanism);
  const auto robot = spec.five_bar();
  nlohmann::json points = nlohmann::json::array();
  if (!o.json) fmt::print("{:>6} {:>10} {:>8} {:>12} {:>12} {:>8} {:>10}\n", "point", "x_mm", "y_mm", "theta1_deg",
                          "theta2_deg", "cond", "fk_err_nm");
  const std::array<double, 3> xs{172.132, 222.132, 272.132};
  const std::array<double, 5> ys{-75.0, -37.5, 0.0, 37.5, 75.0};
  for (std::size_t i = 0; i < xs.size(); ++i) {
    for (std::size_t j = 0; j < ys.size(); ++j) {
      const Vec2 p{units::mm_to_m(xs[i]), units::mm_to_m(ys[j])};
      const Vec2 q = robot.inverse(p);
      const double err_nm = (robot.forward(q) - p).norm() * 1e9;
      const std::string id = fmt::format("x{}y{}", i + 1, j + 1);
      auto pose = pose_json(robot, q, p);
      pose["point"] = id;
      pose["fk_roundtrip_error_nm"] = tidy(err_nm);
      points.push_back(pose);
      if (!o.json) {
        fmt::print("{:>6} {:>10.3f} {:>8.1f} {:>12.6f} {:>12.6f} {:>8.4f} {:>10.2e}\n", id, xs[i], ys[j],
                   units::rad_to_deg(q.x()), units::rad_to_deg(q.y()), robot.condition_number(q), err_nm);
      }
    }
  }
  if (o.json) print_json({{"mechanism", spec.name}, {"points", points}});
}
}  // namespace

void add_kin_command(CLI::App& app) {
  auto* kin = app.add_subcommand("kin", "Five-bar kinematics (thesis eqs. 2.1-2.2)");
  kin->require_subcommand(1);
  auto opts = std::make_shared<KinOptions>();

  auto* fk = kin->add_subcommand("fk", "Forward kinematics: joint angles -> platform point");
  fk->add_option("--theta1-deg", opts->theta1_deg, "Actuator 1 angle (deg)")->required();
  fk->add_option("--theta2-deg", opts->theta2_deg, "Actuator 2 angle (deg)")->required();
  auto* ik = kin->add_subcommand("ik", "Inverse kinematics: platform point -> joint angles");
  ik->add_option("--x-mm", opts->x_mm, "Platform x (mm)")->required();
  ik->add_option("--y-mm", opts->y_mm, "Platform y (mm)")->required();
  auto* grid = kin->add_subcommand("grid", "Inverse kinematics on the thesis's 15 measurement points");
  for (auto* sub : {fk, ik, grid}) {
    sub->add_option("--mechanism", opts->mechanism, "Preset (oc-gu, oc-gl, sc-gu, sc-gl) or JSON file")
        ->capture_default_str();
    sub->add_flag("--json", opts->json, "Print one JSON object with units in its keys");
  }
  fk->callback([opts] { run_fk(*opts); });
  ik->callback([opts] { run_ik(*opts); });
  grid->callback([opts] { run_grid(*opts); });
}

}  // namespace stiffpath::cli
