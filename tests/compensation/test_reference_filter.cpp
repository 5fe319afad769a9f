// Reference filters: exact moving average, consistent rates, shaper delays, and commands a servo can follow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/path_motion.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/job/task_source.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::compensation {
namespace {

constexpr double kRate = 2000.0, kDt = 1.0 / kRate;

// p(t) = p0 + v0·t + a0·t²/2 + j0·t³/6 for t ≥ 0 (one jerk-limited phase), at rest at p0 before.
TaskSample cubic(double t) {
  const Vec2 p0{0.2, -0.05}, v0{0.3, -0.1}, a0{5.0, 2.0}, j0{-200.0, 300.0};
  TaskSample s;
  s.t_s = t;
  if (t < 0) {
    s.position_m = p0;
    return s;
  }
  s.position_m = p0 + v0 * t + a0 * t * t / 2 + j0 * t * t * t / 6;
  s.velocity_m_s = v0 + a0 * t + j0 * t * t / 2;
  s.acceleration_m_s2 = a0 + j0 * t;
  s.jerk_m_s3 = j0;
  return s;
}

// ∫ p over [t − W, t] / W for the cubic above (all of the window at t ≥ W).
Vec2 cubic_average(double t, double W) {
  const auto P = [](double x) {
    const Vec2 p0{0.2, -0.05}, v0{0.3, -0.1}, a0{5.0, 2.0}, j0{-200.0, 300.0};
    return Vec2(p0 * x + v0 * x * x / 2 + a0 * x * x * x / 6 + j0 * std::pow(x, 4) / 24);
  };
  return (P(t) - P(t - W)) / W;
}

TEST(ReferenceFilter, MovingAverageOfACubicIsExact) {
  ReferenceFilterOptions o;
  o.kind = FilterKind::smooth;
  o.smooth_s = 0.004;
  ReferenceFilter f(kRate, o);
  EXPECT_EQ(f.delay_samples(), 8);
  const double W = 8 * kDt;
  for (int k = 0; k < 200; ++k) {
    const TaskSample out = *f.push(cubic(k * kDt));
    const double t = k * kDt;
    if (t < W) continue;
    EXPECT_LT((out.position_m - cubic_average(t, W)).norm(), 1e-13) << k;
    EXPECT_LT((out.velocity_m_s - (cubic(t).position_m - cubic(t - W).position_m) / W).norm(), 1e-12);
    EXPECT_LT((out.acceleration_m_s2 - (cubic(t).velocity_m_s - cubic(t - W).velocity_m_s) / W).norm(), 1e-10);
    EXPECT_LT(out.snap_m_s4.norm(), 1e-9);  // constant jerk: no snap once the window is inside the phase
  }
}

// A rest-to-rest quintic move from (0.2, 0) to (0.25, 0.03) m in 0.1 s (v and a zero at both ends).
TaskSample quintic(double t) {
  const double T = 0.1, tau = std::clamp(t / T, 0.0, 1.0);
  const Vec2 d{0.05, 0.03};
  TaskSample s;
  s.t_s = t;
  s.position_m = Vec2(0.2, 0.0) + (10 * std::pow(tau, 3) - 15 * std::pow(tau, 4) + 6 * std::pow(tau, 5)) * d;
  if (t > 0 && t < T) {
    s.velocity_m_s = 30 * tau * tau * (1 - tau) * (1 - tau) / T * d;
    s.acceleration_m_s2 = 60 * tau * (1 - tau) * (1 - 2 * tau) / (T * T) * d;
    s.jerk_m_s3 = 60 * (1 - 6 * tau + 6 * tau * tau) / (T * T * T) * d;
  }
  return s;
}

TEST(ReferenceFilter, ChainHandsOutItsDelayAfterTheInputAndEndsAtRest) {
  ReferenceFilterOptions o;
  o.kind = FilterKind::smooth;
  FilterChain chain({ReferenceFilter(kRate, o), ReferenceFilter(kRate, o)});
  EXPECT_EQ(chain.delay_samples(), 16);
  int out = 0;
  for (int k = 0; k <= 200; ++k) out += chain.push(quintic(k * kDt)).has_value();
  TaskSample last;
  while (const auto s = chain.drain()) {
    last = *s;
    ++out;
  }
  EXPECT_EQ(out, 201 + 16);
  EXPECT_LT((last.position_m - Vec2(0.25, 0.03)).norm(), 1e-15);
  EXPECT_EQ(last.velocity_m_s, Vec2::Zero());
}

// A smooth 2-D motion for the shaper (all derivatives analytic).
TaskSample wave(double t) {
  const double w = 2 * M_PI * 2.0;
  TaskSample s;
  s.t_s = t;
  s.position_m = Vec2(0.222 + 0.04 * std::sin(w * t), 0.05 * std::cos(w * t));
  s.velocity_m_s = Vec2(0.04 * w * std::cos(w * t), -0.05 * w * std::sin(w * t));
  s.acceleration_m_s2 = Vec2(-0.04 * w * w * std::sin(w * t), -0.05 * w * w * std::cos(w * t));
  s.jerk_m_s3 = Vec2(-0.04 * std::pow(w, 3) * std::cos(w * t), 0.05 * std::pow(w, 3) * std::sin(w * t));
  s.snap_m_s4 = Vec2(0.04 * std::pow(w, 4) * std::sin(w * t), 0.05 * std::pow(w, 4) * std::cos(w * t));
  return s;
}

TEST(ReferenceFilter, ShaperWithMovingFrequencyHasConsistentRates) {
  for (const FilterKind kind : {FilterKind::zv, FilterKind::zvd}) {
    ReferenceFilterOptions o;
    o.kind = kind;
    o.min_frequency_hz = 40.0;
    // A frequency that changes strongly with x (40 … 80 Hz): delays vary by several ms along the path.
    ReferenceFilter f(kRate, o, [](const Vec2& p) { return 60.0 + 500.0 * (p.x() - 0.222); });
    std::vector<TaskSample> out;
    for (int k = 0; k < 2000; ++k) out.push_back(*f.push(wave(k * kDt)));
    for (std::size_t k = 100; k + 1 < out.size(); ++k) {
      const Vec2 v = (out[k + 1].position_m - out[k - 1].position_m) / (2 * kDt);
      const Vec2 a = (out[k + 1].velocity_m_s - out[k - 1].velocity_m_s) / (2 * kDt);
      EXPECT_LT((out[k].velocity_m_s - v).norm(), 2e-4) << core::enum_name(kind) << " " << k;
      EXPECT_LT((out[k].acceleration_m_s2 - a).norm(), 2e-2) << core::enum_name(kind) << " " << k;
    }
  }
}

TEST(ReferenceFilter, ZvDelaysConstantVelocityByItsCentroid) {
  ReferenceFilterOptions o;
  o.kind = FilterKind::zv;
  o.damping_ratio = 0.05;
  o.min_frequency_hz = 50.0;
  ReferenceFilter f(kRate, o, [](const Vec2&) { return 50.0; });
  const double K = std::exp(-0.05 * M_PI / std::sqrt(1 - 0.0025));
  const double half_period = 0.5 / (50.0 * std::sqrt(1 - 0.0025));
  const Vec2 v{0.5, -0.2};
  for (int k = 0; k < 200; ++k) {
    TaskSample s;
    s.t_s = k * kDt;
    s.position_m = Vec2(0.2, 0.0) + v * s.t_s;
    s.velocity_m_s = v;
    const TaskSample out = *f.push(s);
    if (k < 30) continue;
    EXPECT_LT((out.position_m - (s.position_m - v * half_period * K / (1 + K))).norm(), 1e-14);
    EXPECT_LT((out.velocity_m_s - v).norm(), 1e-14);
  }
}

TEST(ReferenceFilter, RefusesBadSettings) {
  ReferenceFilterOptions o;
  o.kind = FilterKind::zv;
  EXPECT_THROW(ReferenceFilter(kRate, o, [](const Vec2&) { return 50.0; }), Error);  // no lowest frequency
  o.min_frequency_hz = 50.0;
  EXPECT_THROW(ReferenceFilter(kRate, o), Error);  // no frequency function
  o.kind = FilterKind::smooth;
  o.smooth_s = 0.0;
  EXPECT_THROW(ReferenceFilter(kRate, o), Error);
  EXPECT_THROW(core::parse_enum<FilterKind>("box"), Error);
}

// The running sum of the moving average stays the sum: over a 20 M-sample job (2 h 47 min at 2 kHz) of an arc
// length growing to 20 km, every output equals the Euler–Maclaurin sum of its window taken afresh in long double.
TEST(ReferenceFilter, RunningSumDoesNotDriftOverALongJob) {
  ReferenceFilterOptions o;
  o.kind = FilterKind::smooth;
  ReferenceFilter f(kRate, o);
  const int w = 8;
  const double W = w * kDt;
  const auto input = [](std::int64_t k) {  // s(t) = v·t + a parabolic ripple of period 37 samples (rates exact)
    const double t = static_cast<double>(k) * kDt, v = 1.0, r = 1e-6, period = 37 * kDt;
    const double u = static_cast<double>(k % 37) * kDt - 0.5 * period;  // within the ripple's period
    FilterSample x;
    x.t_s = t;
    x.x[0] = Vec2(v * t + r * u * u / (period * period), 0.0);
    x.x[1] = Vec2(v + 2.0 * r * u / (period * period), 0.0);
    x.x[2] = Vec2(2.0 * r / (period * period), 0.0);
    return x;
  };
  double worst = 0.0;
  for (std::int64_t k = 0; k < 20'000'000; ++k) {
    const FilterSample out = f.push(input(k), PlannedPoint{});
    if (k % 999'983 != 0 || k < w) continue;
    long double sum = 0.0L;
    for (std::int64_t i = k - w; i <= k; ++i) sum += static_cast<long double>(input(i).x[0].x());
    const FilterSample now = input(k), then = input(k - w);
    sum -= 0.5L * (static_cast<long double>(now.x[0].x()) + static_cast<long double>(then.x[0].x()));
    const long double direct = (static_cast<long double>(kDt) * sum -
                                static_cast<long double>(kDt * kDt / 12.0) * (now.x[1].x() - then.x[1].x()) +
                                static_cast<long double>(std::pow(kDt, 4) / 720.0) * (now.x[3].x() - then.x[3].x())) /
                               static_cast<long double>(W);
    worst = std::max(worst, static_cast<double>(std::abs(static_cast<long double>(out.x[0].x()) - direct)));
  }
  // A few units in the last place of 20 km (3.6e-12 m); the running sum alone, never summed afresh, ends 1.0e-6 m off.
  EXPECT_LT(worst, 1e-10);
}

// The chain rule of motion_along against an independent computation: the closed form of an arc,
// p(t) = c + |r|·(cos θ, sin θ) with θ = θ₀ + σ(t)/r, and of a line, p(t) = a + σ(t)·T, differentiated by central
// differences of seven points in long double (Richardson-extrapolated), for an arc length σ(t) whose rates are
// written out.
TEST(PathMotion, RatesAreThoseOfThePointAtTheArcLength) {
  using Real = long double;
  // σ(t) = 0.02t + 0.3t² + 2t³ − 5t⁴ + 40t⁵ + 0.01·sin 30t: every rate up to the fifth nonzero.
  const auto sigma = [](Real t) {
    return 0.02L * t + 0.3L * t * t + 2.0L * t * t * t - 5.0L * t * t * t * t + 40.0L * t * t * t * t * t +
           0.01L * std::sin(30.0L * t);
  };
  const double t = 0.05;
  const double w = 30.0, sn = 0.01 * std::sin(w * t), cs = 0.01 * std::cos(w * t);
  const std::array<double, 6> s{static_cast<double>(sigma(t)),
                                0.02 + 0.6 * t + 6.0 * t * t - 20.0 * std::pow(t, 3) + 200.0 * std::pow(t, 4) + w * cs,
                                0.6 + 12.0 * t - 60.0 * t * t + 800.0 * std::pow(t, 3) - w * w * sn,
                                12.0 - 120.0 * t + 2400.0 * t * t - std::pow(w, 3) * cs,
                                -120.0 + 4800.0 * t + std::pow(w, 4) * sn,
                                4800.0 + std::pow(w, 5) * cs};
  const Real cx = 0.22L, cy = -0.01L, ax = 0.2L, ay = 0.03L, ux = 0.6L, uy = 0.8L, theta0 = 0.7L;
  for (const double r : {0.004, -0.01, 0.0}) {  // turning left, turning right, straight
    const Real R = r;
    const auto p = [&](Real time, int axis) -> Real {
      if (r == 0.0) return axis == 0 ? ax + sigma(time) * ux : ay + sigma(time) * uy;
      const Real th = theta0 + sigma(time) / R;
      return axis == 0 ? cx + std::abs(R) * std::cos(th) : cy + std::abs(R) * std::sin(th);
    };
    const auto stencil = [&](int order, Real h) {
      static const Real weight[6][7] = {{0, 0, 0, 1, 0, 0, 0},
                                        {-1.L / 60, 3.L / 20, -3.L / 4, 0, 3.L / 4, -3.L / 20, 1.L / 60},
                                        {1.L / 90, -3.L / 20, 3.L / 2, -49.L / 18, 3.L / 2, -3.L / 20, 1.L / 90},
                                        {1.L / 8, -1, 13.L / 8, 0, -13.L / 8, 1, -1.L / 8},
                                        {-1.L / 6, 2, -13.L / 2, 28.L / 3, -13.L / 2, 2, -1.L / 6},
                                        {-1.L / 2, 2, -5.L / 2, 0, 5.L / 2, -2, 1.L / 2}};
      std::array<Real, 2> d{0, 0};
      for (int axis = 0; axis < 2; ++axis) {
        for (int i = 0; i < 7; ++i) d[axis] += weight[order][i] * p(t + (i - 3) * h, axis);
        d[axis] /= std::pow(h, order);
      }
      return d;
    };
    // Richardson's extrapolation over h and h/2: the stencils err by O(h⁶) (orders 1, 2), O(h⁴) (3, 4), O(h²) (5).
    const auto diff = [&](int order) {
      const Real h = 4e-4L, gain = std::pow(2.0L, order <= 2 ? 6 : order <= 4 ? 4 : 2);
      const auto coarse = stencil(order, h), fine = stencil(order, h / 2);
      return Vec2(static_cast<double>((gain * fine[0] - coarse[0]) / (gain - 1)),
                  static_cast<double>((gain * fine[1] - coarse[1]) / (gain - 1)));
    };
    const double th = 0.7 + s[0] / r;
    // The tangent in the direction of increasing σ: d/dσ of the closed forms.
    const Vec2 tangent = r == 0.0 ? Vec2(0.6, 0.8) : Vec2(std::abs(r) / r * Vec2(-std::sin(th), std::cos(th)));
    const Vec2 point(static_cast<double>(p(t, 0)), static_cast<double>(p(t, 1)));
    const auto x = motion_along({point, tangent, r == 0.0 ? 0.0 : 1.0 / r}, s);
    // The differences' own error, relative (truncation and rounding grow with the order).
    const double tolerance[6] = {0, 1e-10, 1e-9, 1e-8, 1e-7, 1e-5};
    for (int i = 1; i < 6; ++i) {
      const Vec2 expected = diff(i);
      EXPECT_LT((x[static_cast<std::size_t>(i)] - expected).norm(), tolerance[i] * (1.0 + expected.norm()))
          << "r " << r << " order " << i << ": " << x[static_cast<std::size_t>(i)].transpose() << " vs " << expected.transpose();
    }
  }
}

// The job's samples for a G-code program through filters and a compensator (at most 10⁵ samples).
std::vector<JointCommand> commands(const std::string& gcode, FilterChain& filters, const Compensator& comp) {
  std::istringstream in(gcode);
  motion::TrajectoryStream stream(in, "test.gcode");
  job::TaskSource tasks(stream, kRate, job::AccelerationSource::analytic, &filters);
  std::vector<JointCommand> out;
  TaskSample s;
  while (out.size() <= 100000 && tasks.next(s)) out.push_back(comp.step(s));
  return out;
}

// Largest change of ω between samples beyond what the commanded α allows, |ω₊ − ω| − Δt·max(|α|, |α₊|)
// per joint: a step in velocity shows in full, a continuous velocity (even with α jumping) gives ≤ 0.
double velocity_jump(const std::vector<JointCommand>& c) {
  double worst = 0.0;
  for (std::size_t k = 0; k + 1 < c.size(); ++k) {
    for (int i = 0; i < 2; ++i) {
      const double allowed = kDt * std::max(std::abs(c[k].qdd_rad_s2[i]), std::abs(c[k + 1].qdd_rad_s2[i]));
      worst = std::max(worst, std::abs(c[k + 1].qd_rad_s[i] - c[k].qd_rad_s[i]) - allowed);
    }
  }
  return worst;
}

void expect_within_limits(const std::vector<JointCommand>& c, const kinematics::Robot& robot) {
  for (const JointCommand& j : c) {
    ASSERT_EQ(j.status, Status::ok);
    for (int i = 0; i < 2; ++i) {
      const auto& lim = robot.joints[static_cast<std::size_t>(i)];
      EXPECT_GE(j.q_rad[i], lim.min_rad);
      EXPECT_LE(j.q_rad[i], lim.max_rad);
      EXPECT_LE(std::abs(j.qd_rad_s[i]), lim.max_velocity_rad_s);
      EXPECT_LE(std::abs(j.qdd_rad_s2[i]), lim.max_acceleration_rad_s2);
    }
  }
}

const char* kLine = "G21 G90 G61\nG0 X247.132 Y-75\nM3 S1000\nG1 Y75 F120000\nM5\n";
const char* kTriangle =
    "G21 G90 G61\nG0 X187.132 Y-60\nM3 S1000\nG1 X257.132 Y-60 F120000\nG1 X222.132 Y60\nG1 X187.132 Y-60\nM5\n";

// The physical model fitted to the thesis's OC data: smooth, so that the command's rates are too (the
// bilinear model's Ċ steps at its grid lines, by up to ~0.02 rad/s of commanded joint velocity at 5 g).
std::shared_ptr<const compliance::Model> thesis_oc() {
  auto loaded = compliance::load_model("thesis-oc-physical");
  return std::shared_ptr<const compliance::Model>(loaded.model.release());
}

TEST(SmoothCommands, MovingAverageRemovesTheVelocityStepOfTheCompensatedCommand) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto model = thesis_oc();
  for (const Method method : {Method::quasi_static, Method::dynamic}) {
    CompensatorOptions co;
    co.method = method;
    const Compensator comp(robot, model, co);
    FilterChain none;
    const auto raw = commands(kLine, none, comp);
    ReferenceFilterOptions o;
    o.kind = FilterKind::smooth;
    // Two moving averages: continuous snap too, which the dynamic offset's T²·δ̈₀ term needs (one
    // average leaves snap steps Δj/W, i.e. velocity steps of T·C·m·Δj/W ≈ 0.1 rad/s).
    FilterChain smooth({ReferenceFilter(kRate, o), ReferenceFilter(kRate, o)});
    const auto smoothed = commands(kLine, smooth, comp);
    // Jerk steps of 5 g / 5 ms through Δ = C·m·a: the raw command's velocity steps by ~0.1 rad/s or more.
    EXPECT_GT(velocity_jump(raw), 0.05) << core::enum_name(method);
    EXPECT_LT(velocity_jump(smoothed), 0.01) << core::enum_name(method);
    expect_within_limits(smoothed, robot);
    EXPECT_EQ(smoothed.size(), raw.size() + 16);
  }
}

TEST(SmoothCommands, ShapedCommandsKeepTheLimits) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto model = thesis_oc();
  const double m = robot.moving_mass_kg;
  const double lowest = lowest_natural_frequency_hz(*model, m, model->bounds());
  ASSERT_GT(lowest, 10.0);
  for (const FilterKind kind : {FilterKind::zv, FilterKind::zvd}) {
    for (const char* job : {kLine, kTriangle}) {
      CompensatorOptions co;
      co.method = Method::dynamic;
      const Compensator comp(robot, model, co);
      ReferenceFilterOptions shaping, smoothing;
      shaping.kind = kind;
      shaping.min_frequency_hz = lowest;
      smoothing.kind = FilterKind::smooth;
      FilterChain chain({ReferenceFilter(kRate, shaping,
                                         [&](const Vec2& p) {
                                           return lowest_natural_frequency_hz(model->compliance(p), m);
                                         }),
                         ReferenceFilter(kRate, smoothing), ReferenceFilter(kRate, smoothing)});
      const auto c = commands(job, chain, comp);
      expect_within_limits(c, robot);
      EXPECT_LT(velocity_jump(c), 0.01) << core::enum_name(kind);
    }
  }
}

}  // namespace
}  // namespace stiffpath::compensation
