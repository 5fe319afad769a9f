// Chord-flattened contours: their feed is reached where the curvature allows it, within every limit and the blend tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <optional>
#include <sstream>
#include <vector>

#include "chord_programs.hpp"
#include "planner_checks.hpp"
#include "stiffpath/motion/sampler.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {
namespace {

struct Sample {
  Vec2 position_m;
  double speed_m_s;
  double distance_m;  // along the sampled path from the first sample
};

// The trajectory sampled at 2 kHz, with the distance travelled (sum of the sample-to-sample chords).
std::vector<Sample> sample_at_2khz(const Trajectory& trajectory) {
  TrajectoryCursor cursor(trajectory);
  Sampler sampler(cursor);
  std::vector<Sample> out;
  while (auto s = sampler.next()) {
    const double d = out.empty() ? 0.0 : out.back().distance_m + (s->position_m - out.back().position_m).norm();
    out.push_back({s->position_m, s->path_speed_m_s, d});
  }
  return out;
}

// At every 2 kHz sample |a| ≤ a_max and |j| ≤ j_max (analytic values), and between samples the
// velocity and acceleration change no faster than the limits allow: by a_max·dt (+ a junction's
// velocity step j·τ²) and by j_max·dt (+ a junction's acceleration step j·τ).
void expect_sampled_within_limits(const Trajectory& trajectory) {
  const MotionLimits limits;
  const double a = limits.max_acceleration_m_s2, j = limits.max_jerk_m_s3, tau = JunctionRules{}.junction_time_s;
  TrajectoryCursor cursor(trajectory);
  Sampler sampler(cursor);
  std::optional<TrajectorySample> previous;
  while (auto s = sampler.next()) {
    ASSERT_LE(s->acceleration_m_s2.norm(), a * (1 + 1e-9)) << "t " << s->t_s;
    ASSERT_LE(s->jerk_m_s3.norm(), j * (1 + 1e-9)) << "t " << s->t_s;
    if (previous) {
      const double dt = s->t_s - previous->t_s;
      ASSERT_LE((s->velocity_m_s - previous->velocity_m_s).norm(), (a * dt + j * tau * tau) * (1 + 1e-9)) << "t " << s->t_s;
      ASSERT_LE((s->acceleration_m_s2 - previous->acceleration_m_s2).norm(), (j * dt + j * tau) * (1 + 1e-9))
          << "t " << s->t_s;
    }
    previous = s;
  }
}

// Distance from p to the polyline through `vertices`.
double distance_to_polyline(const Vec2& p, const std::vector<Vec2>& vertices) {
  double best = INFINITY;
  for (std::size_t k = 0; k + 1 < vertices.size(); ++k) {
    const Vec2 a = vertices[k], d = vertices[k + 1] - a;
    const double u = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + u * d - p).norm());
  }
  return best;
}

std::vector<Vec2> programmed_vertices(const std::string& gcode) {
  std::istringstream in(gcode);
  GcodeReader reader(in, "job.gcode");
  std::vector<Vec2> vertices;
  while (auto s = reader.next()) {
    if (vertices.empty()) vertices.push_back(s->start_m);
    vertices.push_back(s->end_m);
  }
  return vertices;
}

// A jerk-limited speed change between v0 and v1 needs at least this distance (zero acceleration at
// both ends, limits a and j); within it of the contour's ends or of a slower point, the feed is not
// required.
double change_distance_m(double v0, double v1) {
  const MotionLimits limits;
  return speed_change(v0, v1, limits.max_acceleration_m_s2, limits.max_jerk_m_s3).distance_m;
}

TEST(Contours, ChordFlattenedCircleRunsAtItsFeedWithinLimitsAndTolerance) {
  // 0.1 mm chords, 4 decimals (0.1 µm), G64 P0.01: at 200 mm/s on R = 10 mm the centripetal
  // acceleration is 4 m/s² and the jerk v³/R² 80 m/s³, far below 5 g and 9807 m/s³.
  for (const double radius_mm : {10.0, 5.0, 20.0}) {
    const double feed = radius_mm == 20.0 ? 0.3 : 0.2;
    const std::string gcode = test::chord_circle(222.132, 0.0, radius_mm, 0.1, feed * 60000.0);
    const Trajectory trajectory = test::plan_text(gcode);
    SCOPED_TRACE("R = " + std::to_string(radius_mm) + " mm");
    test::expect_within_limits(trajectory, MotionLimits{});
    test::expect_continuous_junctions(trajectory, MotionLimits{});
    expect_sampled_within_limits(trajectory);
    const std::vector<Sample> samples = sample_at_2khz(trajectory);
    // On the arcs the tangential limits are a few % below the machine's (segment_limits.hpp), so the
    // speed changes at both ends take a little longer than from the machine's limits.
    const double length = samples.back().distance_m, ramp = 1.2 * change_distance_m(0.0, feed);
    int checked = 0;
    for (const Sample& s : samples) {
      if (s.distance_m < ramp || s.distance_m > length - ramp) continue;  // speeding up from rest, stopping
      ASSERT_GE(s.speed_m_s, 0.9 * feed) << "at " << s.distance_m * 1e3 << " mm of " << length * 1e3;
      ++checked;
    }
    EXPECT_GT(checked, 200);
    // The blends stay within the tolerance of the programmed chords.
    const std::vector<Vec2> vertices = programmed_vertices(gcode);
    double deviation = 0.0;
    for (const Sample& s : samples) deviation = std::max(deviation, distance_to_polyline(s.position_m, vertices));
    EXPECT_LE(deviation, 0.01e-3);
  }
}

TEST(Contours, OneProfilePerRunIsWhatLiftsTheSpeed) {
  // The same circle with one profile per segment (zero acceleration at every junction) creeps up to
  // its feed and back down over many chords.
  const std::string gcode = test::chord_circle(222.132, 0.0, 10.0, 0.1, 12000.0);
  PlanOptions per_segment;
  per_segment.planner.one_profile_per_run = false;
  const Trajectory runs = test::plan_text(gcode), segments = test::plan_text(gcode, per_segment);
  const double ideal = 2.0 * std::numbers::pi * 0.010 / 0.2;
  // Measured: 1.03 and 1.19 times the length over the feed.
  EXPECT_LT(runs.duration_s(), 1.05 * ideal);
  EXPECT_GT(segments.duration_s(), 1.15 * ideal);
}

TEST(Contours, ExactStopStopsAtEveryChordCorner) {
  // G61 on the same chords: every vertex turns by 10 mrad > 1 mrad, a corner, so the path stops at
  // each one and passes through it exactly.
  const std::string gcode = test::chord_circle(222.132, 0.0, 10.0, 0.1, 12000.0, 4, "G61");
  const Trajectory trajectory = test::plan_text(gcode);
  const std::vector<Vec2> vertices = programmed_vertices(gcode);
  ASSERT_EQ(trajectory.segments().size() + 1, vertices.size());
  for (std::size_t k = 0; k < trajectory.segments().size(); ++k) {
    const PlannedSegment& seg = trajectory.segments()[k];
    EXPECT_EQ(seg.exit_speed_m_s, 0.0);
    EXPECT_EQ(trajectory.evaluate(seg.end_time_s()).position_m, vertices[k + 1]);
  }
  test::expect_continuous_junctions(trajectory, MotionLimits{});
}

// The gear of examples/gear_outline.gcode (make_marking_jobs.py): 24 teeth between radii 36 and
// 40 mm about (222.132, 0), smoothed trapezoidal teeth; 80 chords per tooth, 4 decimals, F 200 mm/s.
double gear_radius_m(double angle_rad) {
  const double phase = std::fmod(angle_rad * 24.0 / (2.0 * std::numbers::pi), 1.0);
  double s = std::clamp(2.5 - std::abs(phase - 0.5) * 6.0, 0.0, 1.0);
  s = 0.5 - 0.5 * std::cos(std::numbers::pi * s);
  return (36.0 + 4.0 * s) * 1e-3;
}

TEST(Contours, GearOutlineReachesItsFeedOnTheTipLands) {
  std::ifstream file(STIFFPATH_SOURCE_DIR "/examples/gear_outline.gcode");
  std::stringstream text;
  text << file.rdbuf();
  const Trajectory trajectory = test::plan_text(text.str());
  test::expect_within_limits(trajectory, MotionLimits{});
  test::expect_continuous_junctions(trajectory, MotionLimits{});
  expect_sampled_within_limits(trajectory);

  // Where the smooth gear curve itself allows 200 mm/s: its curvature (from the circle through
  // neighbouring points of a fine sampling) lets v²κ ≤ a and v³κ² ≤ j, and no slower point, nor the
  // contour's start at rest, lies within a speed change's distance.
  const MotionLimits limits;
  const double feed = 0.2, a = limits.max_acceleration_m_s2, j = limits.max_jerk_m_s3;
  constexpr int n = 24 * 1000;
  std::vector<Vec2> curve(n);
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    curve[i] = gear_radius_m(t) * Vec2(std::cos(t), std::sin(t));
  }
  std::vector<double> slowest(n, feed), step(n);
  for (int i = 0; i < n; ++i) {
    const Vec2 p0 = curve[(i + n - 1) % n], p1 = curve[i], p2 = curve[(i + 1) % n];
    const Vec2 u = p1 - p0, w = p2 - p1, c = p2 - p0;
    const double kappa = 2.0 * std::abs(u.x() * w.y() - u.y() * w.x()) / (u.norm() * w.norm() * c.norm());
    if (kappa > 0.0) slowest[i] = std::min({feed, std::sqrt(a / kappa), std::cbrt(j / (kappa * kappa))});
    step[i] = w.norm();
  }
  std::vector<bool> exempt(n, false);
  auto mark_around = [&](int i, double reach) {
    for (int dir : {1, -1}) {
      double covered = 0.0;
      for (int k = i; covered <= reach; k += dir) {
        exempt[(k % n + n) % n] = true;
        covered += step[(k % n + n) % n];
      }
    }
  };
  for (int i = 0; i < n; ++i) {
    if (slowest[i] < feed) mark_around(i, change_distance_m(slowest[i], feed));
  }
  mark_around(0, change_distance_m(0.0, feed));  // the contour starts and ends at angle 0, at rest

  const Vec2 centre(0.222132, 0.0);
  double allowed = 0.0, fast = 0.0, tip_allowed = 0.0, tip_fast = 0.0;
  const auto& segs = trajectory.segments();
  for (std::size_t k = 0; k < segs.size(); ++k) {
    if (segs[k].path.line < 12 || segs[k].path.line > 1931) continue;  // the contour's G1 lines
    for (int m = 0; m < 8; ++m) {
      const double t = segs[k].start_time_s + segs[k].duration_s * (m + 0.5) / 8;
      const TrajectorySample s = evaluate(segs[k], t);
      const Vec2 r = s.position_m - centre;
      const double angle = std::fmod(std::atan2(r.y(), r.x()) + 2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
      const int i = static_cast<int>(angle / (2.0 * std::numbers::pi) * n) % n;
      if (exempt[i]) continue;
      const double d = segs[k].path.length_m / 8;
      const double phase = std::fmod(angle * 24.0 / (2.0 * std::numbers::pi), 1.0);
      const bool tip = std::abs(phase - 0.5) <= 0.25;
      allowed += d;
      tip_allowed += tip ? d : 0.0;
      if (s.path_speed_m_s >= 0.9 * feed) {
        fast += d;
        tip_fast += tip ? d : 0.0;
      }
    }
  }
  // Measured: the smooth curve allows the feed on 188 mm of its 377 mm (126 mm on the tip lands);
  // the plan holds 180 mm/s or more on all of the tip lands and on 73 % of the 188 mm. The rest lies
  // on the flanks, between fillets whose junctions with the short lines left between them step the
  // curvature (the junction rule bounds v²·Δκ), which the smooth curve does not.
  EXPECT_GT(allowed, 0.150);
  EXPECT_GT(tip_allowed, 0.070);
  EXPECT_GE(tip_fast, 0.99 * tip_allowed);
  EXPECT_GE(fast, 0.70 * allowed);

  // The fillets that let it run keep the contour within the program's G64 P0.01 of its chords
  // (the programmed chords of lines 12-1931, at 9 points of every planned piece of the contour).
  std::istringstream in(text.str());
  GcodeReader reader(in, "gear_outline.gcode");
  std::vector<Vec2> vertices;
  while (auto p = reader.next()) {
    if (p->line < 12 || p->line > 1931) continue;
    if (vertices.empty()) vertices.push_back(p->start_m);
    vertices.push_back(p->end_m);
  }
  ASSERT_GT(vertices.size(), 1900u);
  double deviation = 0.0;
  for (const PlannedSegment& seg : segs) {
    if (seg.path.line < 12 || seg.path.line > 1931) continue;
    for (int m = 0; m <= 8; ++m) {
      const Vec2 p = evaluate(seg, seg.start_time_s + seg.duration_s * m / 8).position_m;
      deviation = std::max(deviation, distance_to_polyline(p, vertices));
    }
  }
  EXPECT_LE(deviation, 0.01e-3 * (1 + 1e-6));
}

}  // namespace
}  // namespace stiffpath::motion
