// The job's reference filters as `stiffpath run` sets them: two moving averages of half the width, and the shaper.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/robot.hpp"

namespace stiffpath::compensation {
namespace {

constexpr double kRate = 2000.0, kDt = 1.0 / kRate;
const Vec2 p0{0.2, -0.05}, v0{0.3, -0.1}, a0{5.0, 2.0}, j0{-200.0, 300.0};

// The moving mass of the robot whose model the shapers use (the smoothing does not use it).
double mass_kg() { return kinematics::load_robot("oc-gu").moving_mass_kg; }

// p(t) = p0 + v0·t + a0·t²/2 + j0·t³/6 from t = 0 (one jerk-limited phase).
TaskSample cubic(double t) {
  TaskSample s;
  s.t_s = t;
  s.position_m = p0 + v0 * t + a0 * t * t / 2 + j0 * t * t * t / 6;
  s.velocity_m_s = v0 + a0 * t + j0 * t * t / 2;
  s.acceleration_m_s2 = a0 + j0 * t;
  s.jerk_m_s3 = j0;
  return s;
}

// Second antiderivative of p: two moving averages of width h give (Q(t) − 2Q(t − h) + Q(t − 2h)) / h².
Vec2 Q(double x) {
  return Vec2(p0 * x * x / 2 + v0 * std::pow(x, 3) / 6 + a0 * std::pow(x, 4) / 24 + j0 * std::pow(x, 5) / 120);
}

TEST(RunFilters, DefaultIsTwoMovingAveragesOfHalfTheWidth) {
  FilterChain chain = make_run_filters(kRate, RunFilterOptions{}, nullptr, mass_kg());
  const double h = 0.004;  // 8 ms in two halves
  EXPECT_EQ(chain.delay_samples(), 2 * static_cast<int>(std::lround(h * kRate)));
  for (int k = 0; k < 200; ++k) {
    const double t = k * kDt;
    const auto out = chain.push(cubic(t));
    if (!out || t < 2 * h) continue;
    const Vec2 expected = (Q(t) - 2.0 * Q(t - h) + Q(t - 2.0 * h)) / (h * h);
    EXPECT_LT((out->position_m - expected).norm(), 1e-12) << "t = " << t;
  }
}

TEST(RunFilters, ZeroWidthAndNoShaperLeaveTheReferenceAlone) {
  RunFilterOptions o;
  o.smooth_s = 0.0;
  FilterChain chain = make_run_filters(kRate, o, nullptr, mass_kg());
  EXPECT_TRUE(chain.empty());
  EXPECT_EQ(chain.delay_samples(), 0);
}

TEST(RunFilters, RefusesWhatRunRefuses) {
  RunFilterOptions wide;
  wide.smooth_s = 2.0;
  EXPECT_THROW(make_run_filters(kRate, wide, nullptr, mass_kg()), Error);
  RunFilterOptions smooth_shaper;
  smooth_shaper.shaper = FilterKind::smooth;
  EXPECT_THROW(make_run_filters(kRate, smooth_shaper, nullptr, mass_kg()), Error);
  RunFilterOptions zv;
  zv.shaper = FilterKind::zv;
  EXPECT_THROW(make_run_filters(kRate, zv, nullptr, mass_kg()), Error);  // no model
  const auto robot = kinematics::load_robot("oc-gu");
  std::shared_ptr<const compliance::Model> model(compliance::load_robot_model(robot).model.release());
  EXPECT_THROW(make_run_filters(kRate, zv, model, robot.moving_mass_kg), Error);  // no frequency
}

TEST(RunFilters, ShaperOverARegionDelaysByHalfTheSlowestDampedPeriod) {
  const auto robot = kinematics::load_robot("oc-gu");
  std::shared_ptr<const compliance::Model> model(compliance::load_robot_model(robot).model.release());
  RunFilterOptions o;
  o.smooth_s = 0.0;
  o.shaper = FilterKind::zv;
  auto region = compliance::GridBounds::none();
  region.include(Vec2(0.222132, -0.075));
  region.include(Vec2(0.222132, 0.075));
  FilterChain chain = make_run_filters(kRate, o, model, robot.moving_mass_kg, region);
  const double f = lowest_natural_frequency_hz(*model, robot.moving_mass_kg, region);
  ASSERT_GT(f, 10.0);
  // ZV: the second impulse comes half a damped period T_d = 1 / (f·√(1 − ζ²)) after the first.
  const double half_period_samples = 0.5 / (f * std::sqrt(1.0 - o.damping_ratio * o.damping_ratio)) * kRate;
  EXPECT_GE(static_cast<double>(chain.delay_samples()), std::floor(half_period_samples));
  EXPECT_LE(static_cast<double>(chain.delay_samples()), std::ceil(half_period_samples) + 2.0);
}

}  // namespace
}  // namespace stiffpath::compensation
