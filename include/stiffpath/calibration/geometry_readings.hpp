// Readings of the tool point by a measuring instrument at commanded joint angles: the geometry calibration's input.
#pragma once

#include <Eigen/Core>

#include <string>
#include <vector>

#include "stiffpath/kinematics/types.hpp"

namespace stiffpath::calibration {

//! The most readings a file may hold: a planned set is ≤ 40 poses, and 10 000 keeps a fit under a second.
inline constexpr int kMaxGeometryReadings = 10000;
//! Joint readings are checked against ±this (deg): a turn and a half either way.
inline constexpr double kMaxJointReading_deg = 540.0;
//! Instrument coordinates are checked against ±this (mm): 10 m, beyond any arm or tracker of such a robot.
inline constexpr double kMaxInstrumentCoordinate_mm = 1e4;

//! One reading: the joint angles the robot was commanded to (and holds), and where the instrument saw
//! the tool point, in the instrument's own frame.
struct GeometryReading {
  int line = 0;                            //!< the file's line (0: not from a file)
  kinematics::Vec2 q_rad = kinematics::Vec2::Zero();  //!< θ1, θ2 as commanded (joint readings)
  Eigen::Vector3d point_m = Eigen::Vector3d::Zero();  //!< x, y (and z when the file has z_mm), instrument frame
  int reading = 1;                         //!< repeated readings of one pose are numbered 1, 2, …
};

//! A readings file: `theta1_deg,theta2_deg,x_mm,y_mm` (optional `z_mm`, `reading`; `#` lines are
//! comments, extra columns are ignored), one row per reading.
struct GeometryReadings {
  std::string source;
  bool has_z = false;  //!< the instrument gave z: its frame is fitted in 3-D
  std::vector<GeometryReading> rows;
};

//! Reads and checks a readings file: every cell finite and within its range (angles ±kMaxJointReading_deg,
//! coordinates ±kMaxInstrumentCoordinate_mm), a (pose, reading) given once, at most kMaxGeometryReadings rows,
//! at least one. Errors name the file, line, column and value; a column in another unit (`x_m`, `theta1_rad`)
//! is refused by name.
GeometryReadings load_geometry_readings(const std::string& path);
//! Writes readings in the same format (z_mm when has_z; reading always), atomically.
void save_geometry_readings(const GeometryReadings& readings, const std::string& path);

}  // namespace stiffpath::calibration
