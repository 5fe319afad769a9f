// A robot and its geometry as JSON in the robot-file format (serialisation kept out of the real-time Robot header).
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::kinematics {

//! The geometry's fields as in robot files (left_actuator_mm … elbows, assembly, and joint_zero_offsets_deg
//! when either offset is not zero).
nlohmann::json geometry_to_json(const FiveBarGeometry& geometry);
//! The robot as JSON, in the file format (units in the key names; paths as resolved).
nlohmann::json to_json(const Robot& robot);

}  // namespace stiffpath::kinematics
