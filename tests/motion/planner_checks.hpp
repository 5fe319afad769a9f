// Test helper: plan a G-code text, and the property checks every planned program must pass.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::test {

inline motion::Trajectory plan_text(const std::string& gcode, const motion::PlanOptions& options = {}) {
  std::istringstream in(gcode);
  return motion::plan_gcode(in, "job.gcode", options);
}

//! Every limit holds at `samples_per_segment` instants inside each segment and at both ends:
//! |v| ≤ min(F, v_max), |a| ≤ a_max, |j| ≤ j_max (relative 1e-9, tangential and normal parts).
inline void expect_within_limits(const motion::Trajectory& trajectory, const motion::MotionLimits& limits,
                                 int samples_per_segment = 16) {
  const double tol = 1 + 1e-9;
  for (const auto& segment : trajectory.segments()) {
    const double cap = std::min(segment.path.feed_m_s, limits.max_velocity_m_s);
    for (int k = 0; k <= samples_per_segment; ++k) {
      const double t = segment.start_time_s + segment.duration_s * k / samples_per_segment;
      const motion::TrajectorySample s = motion::evaluate(segment, t);
      ASSERT_LE(s.velocity_m_s.norm(), cap * tol) << "line " << segment.path.line << " t " << t;
      ASSERT_LE(s.acceleration_m_s2.norm(), limits.max_acceleration_m_s2 * tol) << "line " << segment.path.line;
      ASSERT_LE(s.jerk_m_s3.norm(), limits.max_jerk_m_s3 * tol) << "line " << segment.path.line << " t " << t;
    }
  }
}

//! Junctions: positions meet exactly, velocity and acceleration step by at most j·τ² and j·τ,
//! times chain without gaps, and G61 corners come to rest on both sides.
inline void expect_continuous_junctions(const motion::Trajectory& trajectory, const motion::MotionLimits& limits,
                                        const motion::JunctionRules& rules = {}) {
  const auto& segs = trajectory.segments();
  const double j = limits.max_jerk_m_s3, tau = rules.junction_time_s;
  for (std::size_t k = 0; k + 1 < segs.size(); ++k) {
    const auto &a = segs[k], &b = segs[k + 1];
    ASSERT_EQ(b.start_time_s, a.end_time_s());
    const motion::TrajectorySample end = motion::evaluate(a, a.end_time_s()), start = motion::evaluate(b, b.start_time_s);
    ASSERT_EQ(end.position_m, start.position_m) << "line " << a.path.line;
    ASSERT_LE((end.velocity_m_s - start.velocity_m_s).norm(), j * tau * tau * (1 + 1e-9) + 1e-15) << "line " << a.path.line;
    ASSERT_LE((end.acceleration_m_s2 - start.acceleration_m_s2).norm(), j * tau * (1 + 1e-9) + 1e-12)
        << "line " << a.path.line;
    ASSERT_EQ(a.exit_speed_m_s, b.entry_speed_m_s);
    const double turn = motion::turn_angle_rad(motion::end_tangent(a.path), motion::start_tangent(b.path));
    if (a.path.mode == motion::JunctionMode::exact_stop && turn > rules.corner_angle_rad) {
      ASSERT_EQ(a.exit_speed_m_s, 0.0) << "G61 corner at line " << a.path.line;
    }
  }
  if (!segs.empty()) {
    EXPECT_EQ(segs.front().entry_speed_m_s, 0.0);
    EXPECT_EQ(segs.back().exit_speed_m_s, 0.0);
  }
}

}  // namespace stiffpath::test
