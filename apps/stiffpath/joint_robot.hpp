// The robot a joint file belongs to: --robot, else the one the file records, checked against the file's name and geometry.
#pragma once

#include <string>

#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::cli {

//! Picks the robot for the joint file `path` read by `reader`: the robot named by `robot_flag` (a preset
//! or a robot file); else the robot the file records, when it is a preset; else the default preset
//! (kDefaultRobot), announced on stderr so that no command falls back silently. A file that records a
//! robot that is not a preset needs --robot. A robot whose name or geometry hash differs from what the
//! file records is refused (file-named stiffpath::Error) unless `force`; `verb` says what the command
//! would do ("simulates", "plots").
kinematics::Robot robot_for_joints(const std::string& robot_flag, const job::JointReader& reader,
                                   const std::string& path, bool force, const char* verb);

}  // namespace stiffpath::cli
