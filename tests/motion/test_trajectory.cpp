// Trajectory, sampler and stream: hand-checked thesis moves, tangent arcs, dwells, and streamed = stored samples.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "planner_checks.hpp"

namespace stiffpath::motion {
namespace {

const std::string x_motion = "G21 G90\nG0 X172.132 Y0\nM3 S1000\nG1 X272.132 F120000\nM5\nM2\n";

TEST(Trajectory, ThesisXMotionHandChecked) {
  // 100 mm, 2 m/s, 5 g, 5 ms ramps: 2·(2/49.03325 + 0.005) + (0.1 − 2·(2/49.03325 + 0.005))/2 s.
  const Trajectory t = test::plan_text(x_motion);
  ASSERT_EQ(t.segments().size(), 1u);
  const double ramp = 2.0 / 49.03325 + 0.005;
  EXPECT_NEAR(t.duration_s(), 2 * ramp + (0.1 - 2 * ramp) / 2.0, 1e-14);
  EXPECT_EQ(t.evaluate(0.0).position_m, Vec2(0.172132, 0.0));
  EXPECT_EQ(t.evaluate(t.duration_s()).position_m, Vec2(0.272132, 0.0));
  EXPECT_EQ(t.evaluate(t.duration_s() + 1.0).velocity_m_s, Vec2::Zero());
  const TrajectorySample peak = t.evaluate(0.5 * 0.005 + 0.02);  // on the acceleration plateau
  EXPECT_NEAR(peak.acceleration_m_s2.x(), 49.03325, 1e-9);
  EXPECT_EQ(peak.acceleration_m_s2.y(), 0.0);
  EXPECT_TRUE(peak.laser_on);
  EXPECT_EQ(peak.line, 4);
}

TEST(Trajectory, LineIntoTangentArcDoesNotStopAndArcAccelerationIsCentripetal) {
  // G61, line along +x into a counter-clockwise arc of R = 20 mm tangent to it.
  const Trajectory t = test::plan_text("G0 X180 Y-40\nG61 G1 X220 F6000\nG3 X240 Y-20 I0 J20\n");
  ASSERT_EQ(t.segments().size(), 2u);
  const double v_junction = t.segments()[0].exit_speed_m_s;
  // Curvature step 1/R at zero tangential acceleration: v ≤ sqrt(j·τ·R) = 0.313 m/s > F = 0.1 m/s.
  EXPECT_DOUBLE_EQ(v_junction, 0.1);
  // Mid-arc the speed is the feed and the acceleration purely centripetal: v²/R towards the centre.
  const auto& arc = t.segments()[1];
  const TrajectorySample mid = evaluate(arc, arc.start_time_s + 0.5 * arc.duration_s);
  EXPECT_NEAR(mid.path_speed_m_s, 0.1, 1e-12);
  const Vec2 to_centre = (Vec2(0.220, -0.020) - mid.position_m).normalized();
  EXPECT_NEAR(mid.acceleration_m_s2.dot(to_centre), 0.01 / 0.02, 1e-9);
  EXPECT_NEAR(mid.acceleration_m_s2.norm(), 0.5, 1e-9);
  // The junction's acceleration step is the centripetal one, v²/R = 0.5 m/s².
  const TrajectorySample before = evaluate(t.segments()[0], t.segments()[0].end_time_s());
  const TrajectorySample after = evaluate(arc, arc.start_time_s);
  EXPECT_NEAR((after.acceleration_m_s2 - before.acceleration_m_s2).norm(), 0.5, 1e-12);
}

TEST(Trajectory, DwellHoldsStillForItsDuration) {
  const Trajectory t = test::plan_text("G0 X200 Y0\nM3 S10\nG1 X210 F600\nG4 P0.25\nG1 X220\n");
  ASSERT_EQ(t.segments().size(), 3u);
  const auto& dwell = t.segments()[1];
  EXPECT_EQ(dwell.duration_s, 0.25);
  const TrajectorySample s = evaluate(dwell, dwell.start_time_s + 0.1);
  EXPECT_EQ(s.position_m, Vec2(0.210, 0.0));
  EXPECT_EQ(s.velocity_m_s, Vec2::Zero());
  EXPECT_EQ(s.jerk_m_s3, Vec2::Zero());
  EXPECT_TRUE(s.laser_on);
}

TEST(Sampler, SamplesAtTheRateUntilTheFirstInstantAtOrAfterTheEnd) {
  const Trajectory t = test::plan_text("G0 X200 Y0\nG61 G1 X230 F30000\nY30\n");
  TrajectoryCursor cursor(t);
  Sampler sampler(cursor, 2000.0);
  std::uint64_t k = 0;
  TrajectorySample last;
  while (auto s = sampler.next()) {
    ASSERT_EQ(s->t_s, static_cast<double>(k) / 2000.0);
    const TrajectorySample direct = t.evaluate(s->t_s);
    ASSERT_EQ(s->position_m, direct.position_m);
    ASSERT_EQ(s->acceleration_m_s2, direct.acceleration_m_s2);
    last = *s;
    ++k;
  }
  EXPECT_EQ(k, static_cast<std::uint64_t>(std::ceil(t.duration_s() * 2000.0)) + 1);
  EXPECT_EQ(last.position_m, Vec2(0.230, 0.030));
  EXPECT_EQ(last.velocity_m_s, Vec2::Zero());
  EXPECT_EQ(sampler.segments(), 2u);
}

TEST(Sampler, StreamGivesTheSameSamplesAsTheStoredTrajectory) {
  const std::string job = "G0 X190 Y-30\nM3 S1\nG64 P0.02\nG1 X200 Y-20 F9000\nG2 X210 Y-10 I10 J0\nG1 X250 Y30\nG4 P0.01\nG0 X200 Y0\n";
  const Trajectory t = test::plan_text(job);
  std::istringstream in(job);
  TrajectoryStream stream(in, "job.gcode");
  std::uint64_t n = 0;
  while (auto s = stream.next()) {
    ASSERT_EQ(s->position_m, t.evaluate(s->t_s).position_m) << s->t_s;
    ASSERT_EQ(s->jerk_m_s3, t.evaluate(s->t_s).jerk_m_s3) << s->t_s;
    ++n;
  }
  EXPECT_EQ(n, stream.samples());
  EXPECT_EQ(stream.segments(), t.segments().size());
  EXPECT_GT(n, 100u);
}

TEST(Sampler, EmptyProgramAndBadRate) {
  std::istringstream in("G21 G90 (nothing moves)\nM2\n");
  TrajectoryStream stream(in, "empty.gcode");
  EXPECT_FALSE(stream.next().has_value());
  const Trajectory t;
  TrajectoryCursor cursor(t);
  EXPECT_THROW(Sampler(cursor, 0.0), Error);
  EXPECT_THROW(Sampler(cursor, NAN), Error);
}

}  // namespace
}  // namespace stiffpath::motion
