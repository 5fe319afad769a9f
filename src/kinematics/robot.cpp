// Robot: presets and files, the five-bar it describes, its geometry hash and point checks with joint limits.
#include "stiffpath/kinematics/robot.hpp"

#include <algorithm>
#include <numbers>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/sha256.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::kinematics {

namespace {
constexpr std::string_view kPresetDir = "robots/";
}

FiveBar Robot::five_bar() const { return FiveBar(geometry, margin, {joints[0].min_rad, joints[1].min_rad}); }

std::string Robot::geometry_hash() const { return kinematics::geometry_hash(geometry); }

std::string Robot::source() const { return preset ? "preset " + name : file.label(); }

std::string geometry_text(const FiveBarGeometry& g) {
  // Nanometre resolution: the same text after a round trip through a file in mm.
  const auto mm = [](double m) { return fmt::format("{:.6f}", units::m_to_mm(m) + 0.0); };
  std::string text =
      fmt::format("five-bar;left_actuator_mm={},{};right_actuator_mm={},{};proximal_mm={},{};distal_mm={},{};"
                  "elbows={},{};assembly={}",
                  mm(g.actuator_m[0].x()), mm(g.actuator_m[0].y()), mm(g.actuator_m[1].x()), mm(g.actuator_m[1].y()),
                  mm(g.proximal_m[0]), mm(g.proximal_m[1]), mm(g.distal_m[0]), mm(g.distal_m[1]), g.elbows[0],
                  g.elbows[1], g.assembly);
  // Zero offsets only when there are any, so that every geometry without them keeps its hash. 10⁻⁹ deg: the
  // same text after a round trip through a file in degrees.
  if (g.joint_zero_rad[0] != 0.0 || g.joint_zero_rad[1] != 0.0) {
    const auto deg = [](double rad) { return fmt::format("{:.9f}", units::rad_to_deg(rad) + 0.0); };
    text += fmt::format(";joint_zero_deg={},{}", deg(g.joint_zero_rad[0]), deg(g.joint_zero_rad[1]));
  }
  return text;
}

std::string geometry_hash(const FiveBarGeometry& g) { return core::sha256_hex(geometry_text(g)); }

bool Robot::within_limits(const Vec2& q) const noexcept {
  for (int i = 0; i < 2; ++i) {
    if (!(q[i] >= joints[static_cast<std::size_t>(i)].min_rad && q[i] <= joints[static_cast<std::size_t>(i)].max_rad)) {
      return false;
    }
  }
  return true;
}

std::string Robot::refusal(const Vec2& p) const {
  const FiveBar robot = five_bar();
  const InverseResult r = robot.solve_inverse(p);
  if (r.status != Reach::ok) return robot.explain(p);
  for (std::size_t i = 0; i < 2; ++i) {
    const JointLimit& lim = joints[i];
    double q = r.q[static_cast<Eigen::Index>(i)];
    if (!(q >= lim.min_rad && q <= lim.max_rad)) {
      // Of the angle's turns, name the one nearest to the range (−55°, not 305°, below a −45° limit).
      const double turn = 2.0 * std::numbers::pi;
      if (q > lim.max_rad && lim.min_rad - (q - turn) < q - lim.max_rad) q -= turn;
      return fmt::format("joint {} would be at {:.3f} deg, outside its range [{:.1f}, {:.1f}] deg", lim.name,
                         units::rad_to_deg(q), units::rad_to_deg(lim.min_rad), units::rad_to_deg(lim.max_rad));
    }
  }
  return {};
}

Vec2 Robot::inverse(const Vec2& p) const {
  const std::string why = refusal(p);
  if (!why.empty()) {
    throw Error(fmt::format("point (x = {:.4f} mm, y = {:.4f} mm) refused: {}", units::m_to_mm(p.x()),
                            units::m_to_mm(p.y()), why));
  }
  return five_bar().solve_inverse(p).q;
}

Vec2 Robot::forward(const Vec2& q) const {
  for (std::size_t i = 0; i < 2; ++i) {
    const double angle = q[static_cast<Eigen::Index>(i)];
    const JointLimit& lim = joints[i];
    if (!std::isfinite(angle)) throw Error(fmt::format("joint {} angle is not a finite number: {}", lim.name, angle));
    if (!(angle >= lim.min_rad && angle <= lim.max_rad)) {
      throw Error(fmt::format("joint {} = {:g} rad ({:g} deg) is outside its range [{:.1f}, {:.1f}] deg on robot '{}'{}",
                              lim.name, angle, units::rad_to_deg(angle), units::rad_to_deg(lim.min_rad),
                              units::rad_to_deg(lim.max_rad), name,
                              std::abs(angle) > 2.0 * std::numbers::pi ? " (degrees given where radians are asked?)" : ""));
    }
  }
  return five_bar().forward_checked(q);
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (const auto& file : core::embedded_files()) {
    if (file.path.starts_with(kPresetDir) && file.path.ends_with(".json")) {
      names.emplace_back(file.path.substr(kPresetDir.size(), file.path.size() - kPresetDir.size() - 5));
    }
  }
  // The thesis's order: by build, G_U before G_L (oc-gu, oc-gl, sc-gu, sc-gl); other names alphabetically.
  const auto rank = [](const std::string& n) {
    if (n.ends_with("-gu")) return n.substr(0, n.size() - 3) + "-0";
    if (n.ends_with("-gl")) return n.substr(0, n.size() - 3) + "-1";
    return n;
  };
  std::sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) { return rank(a) < rank(b); });
  return names;
}

Robot load_robot(const std::string& preset_or_path) {
  const std::vector<std::string> presets = preset_names();
  if (std::find(presets.begin(), presets.end(), preset_or_path) != presets.end()) {
    const core::DataRef ref{std::string(kPresetDir) + preset_or_path + ".json", true};
    Robot robot = parse_robot(core::read_data(ref, core::max_json_bytes), ref);
    robot.preset = true;
    return robot;
  }
  const core::DataRef ref = core::parse_data_ref(preset_or_path);
  if (!core::data_exists(ref)) {
    std::string known;
    for (const auto& p : presets) known += (known.empty() ? "" : ", ") + p;
    throw Error(fmt::format("robot '{}' is neither a preset ({}) nor an existing file", preset_or_path, known));
  }
  return parse_robot(core::read_data(ref, core::max_json_bytes), ref);
}

}  // namespace stiffpath::kinematics
