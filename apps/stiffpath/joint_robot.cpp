// robot_for_joints: one rule, shared by simulate, plot and report, for which robot a joint file is read with.
#include "joint_robot.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "robot_flags.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::cli {

kinematics::Robot robot_for_joints(const std::string& robot_flag, const job::JointReader& reader,
                                   const std::string& path, bool force, const char* verb) {
  const std::string& written_for = reader.mechanism();
  kinematics::Robot robot;
  if (!robot_flag.empty()) {
    robot = kinematics::load_robot(robot_flag);
  } else if (!written_for.empty()) {
    const auto presets = kinematics::preset_names();
    if (std::find(presets.begin(), presets.end(), written_for) == presets.end()) {
      throw Error(SourceLocation{path},
                  fmt::format("the joint file was written for robot '{}', which is not a preset: name its robot file "
                              "with --robot",
                              written_for));
    }
    robot = kinematics::load_robot(written_for);
  } else {
    robot = load_robot_flag("");
    fmt::print(stderr, "warning: {}: the joint file does not record its robot; using the default robot '{}' (name another with --robot)\n",
               path, robot.name);
  }
  const std::string& hash = reader.geometry_hash();
  const bool other_name = !written_for.empty() && written_for != robot.name;
  const bool other_geometry = !hash.empty() && hash != robot.geometry_hash();
  if ((other_name || other_geometry) && !force) {
    throw Error(SourceLocation{path},
                fmt::format("the joint file was written for robot '{}' (geometry {}), not for '{}' (geometry {}, {}); "
                            "--force-robot {} it anyway",
                            written_for, hash.empty() ? "not recorded" : hash.substr(0, 12), robot.name,
                            robot.geometry_hash().substr(0, 12), robot.source(), verb));
  }
  return robot;
}

}  // namespace stiffpath::cli
