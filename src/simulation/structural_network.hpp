// The structural network's mechanics, shared by the model and its fit: arm poses, springs, stiffness, compliance.
#pragma once

#include <Eigen/Dense>
#include <array>

#include "stiffpath/kinematics/five_bar.hpp"
#include "stiffpath/simulation/structural_compliance.hpp"

namespace stiffpath::simulation::network {

using compliance::Mat2;
using compliance::Vec2;
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

//! The arm's pose at one platform position: actuator A, elbow B, unit vectors e (A → B) and u (B → C).
struct ArmPose {
  Vec2 A, B, e, u;
  double lp, ld;
};
using Pose = std::array<ArmPose, 2>;

//! Both arms' elements as stiffnesses.
std::array<detail::ArmSprings, 2> arm_springs(const std::array<ArmCompliance, 2>& arms, const kinematics::FiveBarGeometry& g);
//! Platform stiffness (x, y, ψ at C) of one arm: its elbow body (B, ψ_E) condensed out.
Mat3 arm_stiffness(const ArmPose& g, const detail::ArmSprings& a);
//! The compliance at the measured point from the arms' platform stiffness k (their sum) and the base.
Mat2 network_compliance(const Mat3& k, const BaseCompliance& base, const Vec2& offset, const Vec2& p, const Vec2& a0);
//! The same from the arms' poses and springs.
Mat2 network_compliance(const Pose& pose, const std::array<detail::ArmSprings, 2>& arms, const BaseCompliance& base,
                        const Vec2& offset, const Vec2& p, const Vec2& a0);
//! The arms' poses at p (p within reach, q its joint angles).
Pose pose_at(const kinematics::FiveBar& five_bar, const kinematics::Vec2& q, const Vec2& p);
//! The actuators' midpoint A_0, about which the base frame rotates.
Vec2 midpoint(const kinematics::FiveBar& five_bar);

}  // namespace stiffpath::simulation::network
