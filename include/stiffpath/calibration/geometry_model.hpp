// What an instrument reads at commanded joint angles: the five-bar's geometry and the instrument's frame as one parameter vector.
#pragma once

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::calibration {

//! The parameters of a geometry calibration, in this order (SI: m, rad). The instrument's frame is the
//! robot's turned by the start rotation R₀ (from the readings) and then by the small rotation vector
//! w = (rotation_x, rotation_y, rotation_z) about the robot's axes, and shifted by (x, y, z):
//! reading = R₀·exp([w]×)·(C, 0) + t, with C the five-bar's end point at the commanded angles.
enum class GeometryParameter : int {
  left_actuator_x, left_actuator_y, right_actuator_x, right_actuator_y,
  left_proximal, right_proximal, left_distal, right_distal,
  theta1_zero, theta2_zero,
  instrument_rotation_x, instrument_rotation_y, instrument_rotation_z,
  instrument_x, instrument_y, instrument_z,
};
inline constexpr int kGeometryParameters = 16;
//! The robot's own parameters are the first kRobotParameters (actuators, links, zero offsets).
inline constexpr int kRobotParameters = 10;

//! "left_actuator_x_mm" … "instrument_z_mm": the parameter's name with its unit at the edges (mm, deg).
const char* parameter_name(int k) noexcept;
//! The factor from SI to the unit in parameter_name (1e3 for lengths, 180/π for angles).
double parameter_unit_factor(int k) noexcept;

//! The instrument's frame: where it sees a point of the robot's plane.
struct InstrumentFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();     //!< robot frame → instrument frame
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();     //!< the robot's origin in the instrument frame
  //! The instrument's coordinates of the robot-plane point p (z = 0 in the robot frame).
  [[nodiscard]] Eigen::Vector3d to_instrument(const kinematics::Vec2& p) const {
    return rotation * Eigen::Vector3d(p.x(), p.y(), 0.0) + translation_m;
  }
};

//! The parameter vector's meaning for one robot and one start rotation: it reads the vector into a geometry
//! (the robot's working and assembly modes kept) and an instrument frame, and predicts readings.
class GeometryModel {
 public:
  //! `start_rotation`: R₀, the instrument frame's rotation before the fitted small one.
  GeometryModel(const kinematics::Robot& nominal, const Eigen::Matrix3d& start_rotation);

  //! The vector of `geometry` and an instrument frame (its rotation taken relative to R₀, which it must
  //! be close to: the rotation vector of R₀ᵀ·R).
  [[nodiscard]] Eigen::VectorXd pack(const kinematics::FiveBarGeometry& geometry, const InstrumentFrame& frame) const;
  [[nodiscard]] kinematics::FiveBarGeometry geometry(const Eigen::VectorXd& x) const;
  [[nodiscard]] InstrumentFrame instrument(const Eigen::VectorXd& x) const;
  //! The end point at joint readings q for the geometry of x, robot frame (the loop closed as nearly as it
  //! can be where it cannot close, so that a trial step of a fit stays finite).
  [[nodiscard]] static kinematics::Vec2 end_point(const kinematics::FiveBarGeometry& g, const kinematics::Vec2& q);
  //! What the instrument reads at joint readings q for x.
  [[nodiscard]] Eigen::Vector3d reading(const Eigen::VectorXd& x, const kinematics::Vec2& q) const;
  [[nodiscard]] const kinematics::Robot& nominal() const noexcept { return nominal_; }
  [[nodiscard]] const Eigen::Matrix3d& start_rotation() const noexcept { return r0_; }

 private:
  kinematics::Robot nominal_;
  Eigen::Matrix3d r0_;
};

//! The rotation exp([w]×) of a rotation vector w (Rodrigues).
Eigen::Matrix3d rotation_of(const Eigen::Vector3d& w);

}  // namespace stiffpath::calibration
