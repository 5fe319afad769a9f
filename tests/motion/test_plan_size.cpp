// The size of a plan known before sampling (measure_plan, sample_count) against what the sampler really hands out.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

#include "random_program.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::motion {
namespace {

TEST(PlanSize, SampleCountIsTheFirstSampleTimeAtOrAfterTheEndPlusOne) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    const double rate = k % 3 == 0 ? 2000.0 : 1.0 + 1e5 * unit(rng);
    // Whole numbers of periods (where rounding decides) as often as arbitrary durations.
    const double duration = k % 2 == 0 ? std::floor(1e4 * unit(rng)) / rate : 100.0 * unit(rng) * unit(rng);
    const std::uint64_t n = sample_count(duration, rate);
    ASSERT_GE(n, 1u);
    const auto last = n - 1;
    EXPECT_GE(static_cast<double>(last) / rate, duration) << duration << " at " << rate;
    if (last > 0) {
      EXPECT_LT(static_cast<double>(last - 1) / rate, duration) << duration << " at " << rate;
    }
  }
  EXPECT_EQ(sample_count(0.0, 2000.0), 1u);
  EXPECT_EQ(sample_count(1e300, 2000.0), UINT64_MAX);
}

TEST(PlanSize, MeasuredPlanEqualsTheStreamOnRandomProgramsAndRates) {
  std::mt19937_64 rng(7);
  for (int p = 0; p < 12; ++p) {
    const std::string program = test::random_program(rng, 40);
    PlanOptions options;
    options.rate_hz = p % 2 == 0 ? 2000.0 : 333.0 + 97.0 * p;
    std::istringstream a(program), b(program);
    const PlanSize size = measure_plan(a, "random.gcode", options);
    TrajectoryStream stream(b, "random.gcode", options);
    double last_t = 0.0;
    while (auto s = stream.next()) last_t = s->t_s;
    EXPECT_EQ(size.samples, stream.samples()) << "program " << p;
    EXPECT_EQ(size.segments, stream.segments()) << "program " << p;
    EXPECT_LE(size.duration_s, last_t);
    EXPECT_GT(size.duration_s, last_t - 1.0 / options.rate_hz);
  }
  std::istringstream empty("G21\n");
  EXPECT_EQ(measure_plan(empty, "empty.gcode").samples, 0u);
}

TEST(PlanSize, MeasuringTakesTimeInSegmentsNotInDuration) {
  // Forty minutes of dwells: 4.8 million samples at 2 kHz, measured without making one.
  std::string program = "G0 X200 Y0\n";
  for (int k = 0; k < 40; ++k) program += "G4 P60\n";
  std::istringstream in(program);
  const PlanSize size = measure_plan(in, "long.gcode");
  EXPECT_EQ(size.segments, 40u);
  EXPECT_DOUBLE_EQ(size.duration_s, 2400.0);
  EXPECT_EQ(size.samples, 4'800'001u);
}

TEST(MotionLimitsRanges, EachLimitIsRefusedOutsideItsDocumentedRange) {
  const double bad_velocity[] = {0.0, -1.0, 1e-4, 101.0, std::nan(""), INFINITY};
  for (const double v : bad_velocity) {
    MotionLimits l;
    l.max_velocity_m_s = v;
    EXPECT_THROW(validate(l), Error) << v;
  }
  const double bad_jerk[] = {1e-100, 0.5, 2e8, std::nan("")};
  for (const double j : bad_jerk) {
    MotionLimits l;
    l.max_jerk_m_s3 = j;
    EXPECT_THROW(validate(l), Error) << j;
  }
  MotionLimits l;
  l.max_acceleration_m_s2 = 2e4;
  EXPECT_THROW(validate(l), Error);
  l.max_acceleration_m_s2 = 1e4;
  l.max_jerk_m_s3 = 1e8;
  l.max_velocity_m_s = 100.0;
  EXPECT_NO_THROW(validate(l));
}

}  // namespace
}  // namespace stiffpath::motion
