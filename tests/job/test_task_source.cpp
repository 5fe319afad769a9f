// TaskSource's reference filters on the planned path: laser-on points stay on the programmed geometry at any
// smoothing and shaper, laser edges where the strokes begin and end, smooth motion, stops that are stops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/job.hpp"
#include "stiffpath/job/task_source.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::job {
namespace {

using compensation::FilterChain;
using compensation::FilterKind;
using compensation::TaskSample;
using compensation::Vec2;

constexpr double kRate = 2000.0, kDt = 1.0 / kRate;

// Two strokes with a rapid between them (G61): along +x at y = -20 mm, then back along -x at y = -19 mm.
const char* kTwoStrokes =
    "G21 G90 G61\nG0 X190 Y-30\nG0 X200 Y-20\nM3 S1000\nG1 X240 Y-20 F120000\nM5\nG0 X240 Y-19\nM3 S1000\nG1 X200 Y-19\nM5\nM2\n";
// A full circle of radius 10 mm about (222, 0) mm near the acceleration limit (G61, a lead-in rapid).
const char* kCircle = "G21 G90 G61\nG0 X222 Y0\nG0 X232 Y0\nM3 S1000\nG2 X232 Y0 I-10 J0 F60000\nM5\nM2\n";
// A 40 mm square blended within P = 1 mm (G64) at 0.1 m/s: its corners are rounded, never stopped at. (Faster, or
// with a tighter P, the planner stops at these corners instead: a fillet's curvature step would cost more time.)
const char* kBlendedSquare =
    "G21 G90 G64 P1\nG0 X190 Y-30\nG0 X200 Y-20\nM3 S1000\nG1 X240 Y-20 F6000\nG1 X240 Y20\nG1 X200 Y20\nG1 X200 Y-20\n"
    "G1 X240 Y-20\nM5\nM2\n";
// A straight stroke along y (exact stop at both ends), 2 m/s at 5 g.
const char* kLine = "G21 G90 G61\nG0 X240 Y-70\nG0 X247.132 Y-75\nM3 S1000\nG1 Y75 F120000\nM5\nM2\n";

Vec2 mm(double x, double y) { return {x * 1e-3, y * 1e-3}; }

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double u = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + u * d)).norm();
}

struct Filters {
  double smooth_ms = 8.0;
  FilterKind shaper = FilterKind::none;
};

std::string describe(const Filters& s) {
  return "smooth " + std::to_string(s.smooth_ms) + " ms, shaper " + std::string(core::enum_name(s.shaper));
}

// The robot's compliance model, for the shapers' frequency.
std::shared_ptr<const compliance::Model> model() {
  static const std::shared_ptr<const compliance::Model> m(
      compliance::load_robot_model(kinematics::load_robot("oc-gu")).model.release());
  return m;
}

// The rectangle a program's plan covers.
compliance::GridBounds region(const std::string& gcode) {
  std::istringstream in(gcode);
  motion::TrajectoryStream stream(in, "job.gcode");
  auto box = compliance::GridBounds::none();
  while (const auto s = stream.next()) box.include(s->position_m);
  return box;
}

// The compensation's input for a program, as `stiffpath run` makes it (at most 10⁵ samples).
std::vector<TaskSample> reference(const std::string& gcode, const Filters& setup,
                                  AccelerationSource acceleration = AccelerationSource::analytic) {
  compensation::RunFilterOptions o;
  o.smooth_s = setup.smooth_ms * 1e-3;
  o.shaper = setup.shaper;
  const double mass_kg = kinematics::load_robot("oc-gu").moving_mass_kg;
  FilterChain filters = compensation::make_run_filters(kRate, o, model(), mass_kg, region(gcode));
  std::istringstream in(gcode);
  motion::TrajectoryStream stream(in, "job.gcode");
  TaskSource tasks(stream, kRate, acceleration, &filters);
  EXPECT_EQ(tasks.follows_path(), !filters.empty());
  std::vector<TaskSample> out;
  TaskSample s;
  while (out.size() < 100000 && tasks.next(s)) out.push_back(s);
  return out;
}

const std::vector<Filters>& setups() {
  static const std::vector<Filters> all{{0.0, FilterKind::none},  {8.0, FilterKind::none}, {20.0, FilterKind::none},
                                      {100.0, FilterKind::none}, {8.0, FilterKind::zv},  {8.0, FilterKind::zvd}};
  return all;
}

// The runs of consecutive laser-on samples: [first, last] indices.
std::vector<std::pair<std::size_t, std::size_t>> strokes(const std::vector<TaskSample>& s) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (!s[k].laser_on) continue;
    if (k == 0 || !s[k - 1].laser_on) out.emplace_back(k, k);
    out.back().second = k;
  }
  return out;
}

TEST(TaskSourcePath, TwoStrokesKeepEveryLaserOnSampleOnTheStrokesAndSwitchWhereTheyBeginAndEnd) {
  const Vec2 a0 = mm(200, -20), a1 = mm(240, -20), b0 = mm(240, -19), b1 = mm(200, -19);
  for (const Filters& setup : setups()) {
    const auto s = reference(kTwoStrokes, setup);
    const auto runs = strokes(s);
    ASSERT_EQ(runs.size(), 2u) << describe(setup);
    const Vec2 begin[2] = {a0, b0}, end[2] = {a1, b1};
    for (std::size_t r = 0; r < 2; ++r) {
      const auto [first, last] = runs[r];
      ASSERT_GT(first, 0u);
      if (last + 1 == s.size()) continue;  // unfiltered, the plan's last sample has the laser on
      double worst = 0.0;
      for (std::size_t k = first; k <= last; ++k) worst = std::max(worst, distance_to_segment(s[k].position_m, begin[r], end[r]));
      EXPECT_LT(worst, 1e-10) << describe(setup) << " stroke " << r;  // G61: no deviation but rounding
      // The laser switches on between the sample before and the first one, and off after the last: the stroke's
      // ends lie within the travel of one sample period of them.
      EXPECT_LE((s[first].position_m - begin[r]).norm(), (s[first].position_m - s[first - 1].position_m).norm() + 1e-11)
          << describe(setup) << " stroke " << r;
      EXPECT_LE((s[last].position_m - end[r]).norm(), (s[last + 1].position_m - s[last].position_m).norm() + 1e-11)
          << describe(setup) << " stroke " << r;
      // Filtered, the laser never fires standing still (it rests at each end of a stroke, laser off).
      if (setup.smooth_ms > 0.0 || setup.shaper != FilterKind::none) {
        for (std::size_t k = first; k <= last; ++k) EXPECT_GT(s[k].velocity_m_s.norm(), 0.0) << describe(setup) << " " << k;
      }
    }
  }
}

TEST(TaskSourcePath, CircleStaysOnItsRadius) {
  const Vec2 centre = mm(222, 0);
  for (const Filters& setup : setups()) {
    const auto s = reference(kCircle, setup);
    double worst = 0.0, peak_acceleration = 0.0;
    std::size_t on = 0;
    for (const auto& p : s) {
      if (!p.laser_on) continue;
      ++on;
      worst = std::max(worst, std::abs((p.position_m - centre).norm() - 0.010));
      peak_acceleration = std::max(peak_acceleration, p.acceleration_m_s2.norm());
    }
    EXPECT_GT(on, 50u) << describe(setup);
    EXPECT_LT(worst, 1e-10) << describe(setup);
    // At the acceleration limit a Cartesian moving average of W/2 would pull the circle in by a·(W/2)²/24 per average.
    EXPECT_GT(peak_acceleration, 30.0) << describe(setup);
    EXPECT_EQ(strokes(s).size(), 1u) << describe(setup);
  }
}

TEST(TaskSourcePath, BlendedContourStaysWithinItsTolerance) {
  const Vec2 corner[4] = {mm(200, -20), mm(240, -20), mm(240, 20), mm(200, 20)};
  const double P = 1e-3;
  for (const Filters& setup : setups()) {
    const auto s = reference(kBlendedSquare, setup);
    double worst = 0.0;
    for (const auto& p : s) {
      if (!p.laser_on) continue;
      double d = std::numeric_limits<double>::infinity();
      for (int i = 0; i < 4; ++i) d = std::min(d, distance_to_segment(p.position_m, corner[i], corner[(i + 1) % 4]));
      worst = std::max(worst, d);
    }
    EXPECT_LT(worst, P + 1e-10) << describe(setup);
    EXPECT_GT(worst, 0.1 * P) << describe(setup);  // the corners are blended (passed at speed)
    EXPECT_EQ(strokes(s).size(), 1u) << describe(setup);
  }
}

// The rates are those of the positions (central differences, to the differences' own error: Δt²/6 of the jerk, and
// Δt/4 of an acceleration step where the curvature steps) along arcs, blends and lines alike: the chain rule on the
// path, not a Cartesian filter.
TEST(TaskSourcePath, VelocityIsTheRateOfThePositions) {
  for (const char* job : {kCircle, kBlendedSquare, kTwoStrokes}) {
    for (const Filters& setup : setups()) {
      // (Averaged over 100 ms the speed through the square's 0.12 mm blends is that of its sides, 0.5 m/s: each blend
      // is passed within one sample, which central differences cannot resolve; docs/compensation.md.)
      if (job == kBlendedSquare && setup.smooth_ms > 20.0) continue;
      const auto s = reference(job, setup);
      double worst = 0.0;
      for (std::size_t k = 1; k + 1 < s.size(); ++k) {
        const Vec2 v = (s[k + 1].position_m - s[k - 1].position_m) / (2 * kDt);
        const double jerk = std::max({s[k - 1].jerk_m_s3.norm(), s[k].jerk_m_s3.norm(), s[k + 1].jerk_m_s3.norm()});
        const double step = std::max((s[k + 1].acceleration_m_s2 - s[k].acceleration_m_s2).norm(),
                                     (s[k].acceleration_m_s2 - s[k - 1].acceleration_m_s2).norm());
        // (and 1 µm/s: the moving average's Euler–Maclaurin sum is exact to a few 1e-10 of its rates' differences)
        const double e = (v - s[k].velocity_m_s).norm() / (kDt * kDt / 6.0 * jerk + kDt / 4.0 * step + 1e-6);
        worst = std::max(worst, e);
      }
      EXPECT_LT(worst, 1.0) << describe(setup);
    }
  }
}

// Along a straight stroke the filtered jerk is continuous: it changes by at most 2j·Δt/(W/2) a sample (each
// average of W/2 turns a jerk step, of up to 2j, into a ramp), where the plan steps by j or more.
TEST(TaskSourcePath, JerkIsContinuousAlongAStraightStroke) {
  const double j = motion::MotionLimits{}.max_jerk_m_s3;
  const auto largest_step = [](const std::vector<TaskSample>& s) {
    double worst = 0.0;
    for (std::size_t k = 0; k + 1 < s.size(); ++k) worst = std::max(worst, (s[k + 1].jerk_m_s3 - s[k].jerk_m_s3).norm());
    return worst;
  };
  EXPECT_GT(largest_step(reference(kLine, {0.0, FilterKind::none})), 0.99 * j);
  for (const double w_ms : {8.0, 20.0}) {
    const double half_s = 0.5 * w_ms * 1e-3;
    EXPECT_LT(largest_step(reference(kLine, {w_ms, FilterKind::none})), 2.001 * j * kDt / half_s) << w_ms;
  }
}

// Every stop of the plan rests for the filters' delay and one sample: the job is that much longer per stop (three
// stops between the four moves of the two-stroke job, each a corner under G61), and the delay at the end.
TEST(TaskSourcePath, EveryStopRestsForTheFiltersDelay) {
  const auto raw = reference(kTwoStrokes, {0.0, FilterKind::none});
  const auto smoothed = reference(kTwoStrokes, {8.0, FilterKind::none});
  EXPECT_EQ(smoothed.size(), raw.size() + 16 + 3 * 17);
  std::istringstream in(kTwoStrokes);
  const motion::PlanSize size = motion::measure_plan(in, "job.gcode", {}, 17);
  EXPECT_EQ(size.stops, 3u);
  EXPECT_EQ(size.rest_samples_added, 3u * 17u);
  // At each stop the filtered motion comes to rest at the corner itself.
  for (const Vec2& corner : {mm(240, -20), mm(240, -19), mm(200, -20)}) {
    bool rested = false;
    for (const auto& p : smoothed) rested |= (p.position_m - corner).norm() < 1e-12 && p.velocity_m_s.norm() < 1e-9;
    EXPECT_TRUE(rested);
  }
}

// A dwell of its own counts as the rest, and its laser fires for the dwell's time only.
TEST(TaskSourcePath, DwellWithTheLaserOnFiresForItsDurationOnly) {
  const char* job = "G21 G90 G61\nG0 X190 Y0\nG0 X200 Y0\nM3 S1000\nG4 P0.05\nM5\nG0 X210 Y0\nM2\n";
  const auto s = reference(job, {8.0, FilterKind::none});
  const auto runs = strokes(s);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_NEAR(static_cast<double>(runs[0].second - runs[0].first + 1) * kDt, 0.05, 2.5 * kDt);
  for (std::size_t k = runs[0].first; k <= runs[0].second; ++k) EXPECT_LT((s[k].position_m - mm(200, 0)).norm(), 1e-9);
}

// Power stays in time with the filtered motion: with M4 it is S·min(1, v/F) at the sample's own speed, with M3 S;
// standing at the corners of one stroke (the rests the filters add) the laser stays on at power 0.
TEST(TaskSourcePath, PowerFollowsTheFilteredSpeed) {
  const Vec2 corners[2] = {mm(240, -20), mm(240, 20)};
  for (const char* mode : {"M3", "M4"}) {
    const std::string job = std::string("G21 G90 G61\nG0 X190 Y-30\nG0 X200 Y-20\n") + mode +
                            " S500\nG1 X240 Y-20 F6000\nG1 X240 Y20\nG1 X200 Y-20\nM5\nM2\n";
    for (const Filters& setup : {Filters{8.0, FilterKind::none}, Filters{8.0, FilterKind::zvd}}) {
      const auto s = reference(job, setup);
      ASSERT_EQ(strokes(s).size(), 1u) << mode;
      std::size_t standing[2] = {0, 0};
      for (const auto& p : s) {
        if (!p.laser_on) {
          EXPECT_EQ(p.power, 0.0);
          continue;
        }
        const double v = p.velocity_m_s.norm();
        const double moving = std::string(mode) == "M4" ? 0.5 * std::min(1.0, v / 0.1) : 0.5;
        bool near_corner = false;
        for (int c = 0; c < 2; ++c) {
          const double d = (p.position_m - corners[c]).norm();
          near_corner |= d < 1e-9;
          standing[c] += d < 1e-12 && v < 1e-12;  // at rest there, to rounding
          if (d < 1e-12 && v < 1e-12) {
            EXPECT_EQ(p.power, 0.0) << mode << " " << describe(setup);
          }
        }
        // Within a nanometre of a corner it may count as standing (power 0) or as moving.
        if (!near_corner || p.power != 0.0) {
          EXPECT_NEAR(p.power, moving, 1e-12) << mode << " " << describe(setup) << " v " << v;
        }
      }
      EXPECT_GT(standing[0], 0u) << mode;
      EXPECT_GT(standing[1], 0u) << mode;
    }
  }
}

// The thesis's numerical acceleration is that of the filtered positions: the same points, and accelerations within
// the central difference's error of the analytic ones.
TEST(TaskSourcePath, NumericAccelerationDifferentiatesTheFilteredPositions) {
  const auto analytic = reference(kCircle, {8.0, FilterKind::none});
  const auto numeric = reference(kCircle, {8.0, FilterKind::none}, AccelerationSource::numeric);
  ASSERT_EQ(analytic.size(), numeric.size());
  double snap = 0.0;
  for (const auto& p : analytic) snap = std::max(snap, p.snap_m_s4.norm());
  for (std::size_t k = 0; k < analytic.size(); ++k) {
    EXPECT_EQ(analytic[k].position_m, numeric[k].position_m);
    EXPECT_LT((analytic[k].acceleration_m_s2 - numeric[k].acceleration_m_s2).norm(), kDt * kDt / 12.0 * snap + 1e-6);
  }
}

// Samples from a source without planned segments (a recorded trajectory) get the planned point itself filtered, as
// the filter chain alone does.
class Recorded final : public motion::SampleSource {
 public:
  explicit Recorded(std::vector<motion::TrajectorySample> samples) : samples_(std::move(samples)) {}
  std::optional<motion::TrajectorySample> next() override {
    if (i_ == samples_.size()) return std::nullopt;
    return samples_[i_++];
  }

 private:
  std::vector<motion::TrajectorySample> samples_;
  std::size_t i_ = 0;
};

TEST(TaskSourcePath, WithoutSegmentsThePointItselfIsFiltered) {
  std::istringstream in(kCircle);
  motion::TrajectoryStream stream(in, "job.gcode");
  std::vector<motion::TrajectorySample> planned;
  while (const auto s = stream.next()) planned.push_back(*s);
  Recorded recorded(planned);
  FilterChain filters(compensation::smoothing_filters(kRate, 0.008)), alone(compensation::smoothing_filters(kRate, 0.008));
  TaskSource tasks(recorded, kRate, AccelerationSource::analytic, &filters);
  EXPECT_FALSE(tasks.follows_path());
  std::vector<TaskSample> expected;
  for (const auto& p : planned) expected.push_back(*alone.push(to_task_sample(p)));
  while (const auto s = alone.drain()) expected.push_back(*s);
  std::vector<TaskSample> got;
  TaskSample s;
  while (tasks.next(s)) got.push_back(s);
  ASSERT_EQ(got.size(), expected.size());
  for (std::size_t k = 0; k < got.size(); ++k) EXPECT_EQ(got[k].position_m, expected[k].position_m);
}

}  // namespace
}  // namespace stiffpath::job
