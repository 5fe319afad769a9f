// Machine limits of the path motion (speed, acceleration, jerk) and the documented defaults.
#pragma once

#include <Eigen/Core>

#include "stiffpath/core/units.hpp"

namespace stiffpath::motion {

using Vec2 = Eigen::Vector2d;  //!< a point (m) or a vector in the robot's XY frame

//! Default acceleration: 5 g, the highest acceleration of the thesis's tests (§4.5).
inline constexpr double default_acceleration_m_s2 = 5.0 * units::standard_gravity_m_s2;
//! Default time for the acceleration to ramp from 0 to its maximum: 5 ms, ten samples of the
//! thesis's 2 kHz loop (fig. 4.3), so every ramp is resolved by the compensator. See docs/motion.md.
inline constexpr double default_jerk_ramp_time_s = 0.005;
//! Default speed: 2 m/s keeps both joints below 28 rad/s everywhere in the workspace (the presets
//! allow 40 rad/s) and is about the peak speed of the thesis's 150 mm move at 5 g.
inline constexpr double default_max_velocity_m_s = 2.0;

//! The default jerk for an acceleration limit: a / default_jerk_ramp_time_s (m/s³).
constexpr double default_jerk_m_s3(double max_acceleration_m_s2) noexcept {
  return max_acceleration_m_s2 / default_jerk_ramp_time_s;
}

//! Limits on the path's velocity, acceleration and jerk vectors (Euclidean norms in the XY plane,
//! centripetal parts included on arcs). Thesis §4.3: "trapezoidal acceleration profile … limiting
//! velocity, acceleration and jerk".
struct MotionLimits {
  double max_velocity_m_s = default_max_velocity_m_s;                        //!< |v| (m/s); also the G0 speed
  double max_acceleration_m_s2 = default_acceleration_m_s2;                  //!< |a| (m/s²); 49.03 = 5 g
  double max_jerk_m_s3 = default_jerk_m_s3(default_acceleration_m_s2);        //!< |j| (m/s³); 9807 = 5 g / 5 ms
};

//! The ranges a MotionLimits field must lie in (SI). Beyond them no planar robot moves, and the
//! planner's durations and sample counts stop being meaningful (a jerk of 1e-100 would make every
//! move last longer than the universe has existed).
inline constexpr double min_velocity_limit_m_s = 1e-3;        //!< 1 mm/s
inline constexpr double max_velocity_limit_m_s = 100.0;       //!< 100 m/s
inline constexpr double min_acceleration_limit_m_s2 = 1e-2;   //!< about 1 mg
inline constexpr double max_acceleration_limit_m_s2 = 1e4;    //!< about 1000 g
inline constexpr double min_jerk_limit_m_s3 = 1.0;            //!< 1 m/s³
inline constexpr double max_jerk_limit_m_s3 = 1e8;            //!< 1e8 m/s³ (1000 g in 0.1 ms)

//! Throws stiffpath::Error naming the field unless every limit is finite and within its range above.
void validate(const MotionLimits& limits);

}  // namespace stiffpath::motion
