// Chord-flattened contours: their feed is reached where the curvature allows it, within every limit and the blend tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <vector>

#include "chord_programs.hpp"
#include "planner_checks.hpp"
#include "random_cases.hpp"
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
  // acceleration is 4 m/s² and the jerk v³/R² 80 m/s³, far below 5 g and 9807 m/s³. The chords
  // blended (a fillet at each vertex) or fitted (--chords fit: biarcs of the circle's own curvature).
  // Measured (dev build), blended / fitted: R 5 mm 0.1674 / 0.1726 s, R 10 mm 0.3235 / 0.3244 s,
  // R 20 mm 0.4308 / 0.4312 s.
  for (const bool fit : {false, true})
  for (const double radius_mm : {10.0, 5.0, 20.0}) {
    const double feed = radius_mm == 20.0 ? 0.3 : 0.2;
    const std::string gcode = test::chord_circle(222.132, 0.0, radius_mm, 0.1, feed * 60000.0);
    PlanOptions options;
    options.planner.junction.fit_chords = fit;
    const Trajectory trajectory = test::plan_text(gcode, options);
    SCOPED_TRACE("R = " + std::to_string(radius_mm) + (fit ? " mm, fitted" : " mm, blended"));
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

std::string gear_program() {
  std::ifstream file(STIFFPATH_SOURCE_DIR "/examples/gear_outline.gcode");
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Where the smooth gear curve itself allows 200 mm/s: its curvature (from the circle through
// neighbouring points of a fine sampling) lets v²κ ≤ a and v³κ² ≤ j, and no slower point, nor the
// contour's start at rest, lies within a speed change's distance. How much of that length (m) the
// plan covers, and how much at ≥ 90 % of the feed; the same on the tip lands.
struct GearShare {
  double allowed = 0.0, fast = 0.0, tip_allowed = 0.0, tip_fast = 0.0;
};

GearShare gear_share(const Trajectory& trajectory) {
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
  GearShare share;
  for (const PlannedSegment& seg : trajectory.segments()) {
    if (seg.path.line < 12 || seg.path.line > 1931) continue;  // the contour's G1 lines
    for (int m = 0; m < 8; ++m) {
      const double t = seg.start_time_s + seg.duration_s * (m + 0.5) / 8;
      const TrajectorySample s = evaluate(seg, t);
      const Vec2 r = s.position_m - centre;
      const double angle = std::fmod(std::atan2(r.y(), r.x()) + 2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
      const int i = static_cast<int>(angle / (2.0 * std::numbers::pi) * n) % n;
      if (exempt[i]) continue;
      const double d = seg.path.length_m / 8;
      const double phase = std::fmod(angle * 24.0 / (2.0 * std::numbers::pi), 1.0);
      const bool tip = std::abs(phase - 0.5) <= 0.25;
      share.allowed += d;
      share.tip_allowed += tip ? d : 0.0;
      if (s.path_speed_m_s >= 0.9 * feed) {
        share.fast += d;
        share.tip_fast += tip ? d : 0.0;
      }
    }
  }
  return share;
}

// How far the planned gear contour (lines 12-1931, at 9 points of every planned piece) strays from
// the programmed chords (m).
double gear_deviation_m(const Trajectory& trajectory, const std::string& text) {
  std::istringstream in(text);
  GcodeReader reader(in, "gear_outline.gcode");
  std::vector<Vec2> vertices;
  while (auto p = reader.next()) {
    if (p->line < 12 || p->line > 1931) continue;
    if (vertices.empty()) vertices.push_back(p->start_m);
    vertices.push_back(p->end_m);
  }
  EXPECT_GT(vertices.size(), 1900u);
  double deviation = 0.0;
  for (const PlannedSegment& seg : trajectory.segments()) {
    if (seg.path.line < 12 || seg.path.line > 1931) continue;
    for (int m = 0; m <= 8; ++m) {
      const Vec2 p = evaluate(seg, seg.start_time_s + seg.duration_s * m / 8).position_m;
      deviation = std::max(deviation, distance_to_polyline(p, vertices));
    }
  }
  return deviation;
}

// The time the plan spends on the gear contour (lines 12-1931), s.
double gear_contour_s(const Trajectory& trajectory) {
  double duration = 0.0;
  for (const PlannedSegment& seg : trajectory.segments()) {
    if (seg.path.line >= 12 && seg.path.line <= 1931) duration += seg.duration_s;
  }
  return duration;
}

TEST(Contours, GearOutlineReachesItsFeedOnTheTipLands) {
  const std::string text = gear_program();
  const Trajectory trajectory = test::plan_text(text);
  test::expect_within_limits(trajectory, MotionLimits{});
  test::expect_continuous_junctions(trajectory, MotionLimits{});
  expect_sampled_within_limits(trajectory);

  // Measured (dev build): the smooth curve allows the feed on 185 mm of the planned 376 mm (79 mm on
  // the tip lands); the plan holds 180 mm/s or more on all of the tip lands and on 92.9 % of the
  // 185 mm (87.3 % while the flanks' uneven chords got fillets and lines between them, not biarcs).
  // The rest lies on the flanks next to the root and tip fillets, where the chords turn by 9-35° and
  // the arcs' curvature steps from one corner to the next (the junction rule bounds v²·Δκ): the
  // plan must pass those junctions below their bounds, which the smooth curve does not have.
  const GearShare share = gear_share(trajectory);
  EXPECT_GT(share.allowed, 0.150);
  EXPECT_GT(share.tip_allowed, 0.070);
  EXPECT_GE(share.tip_fast, 0.99 * share.tip_allowed);
  EXPECT_GE(share.fast, 0.90 * share.allowed);

  // The fillets that let it run keep the contour within the program's G64 P0.01 of its chords.
  EXPECT_LE(gear_deviation_m(trajectory, text), 0.01e-3 * (1 + 1e-6));
}

TEST(Contours, JoiningRunsIsWhatLiftsTheGearFlanks) {
  // Without joining, every run between two curvature steps of the flanks starts and ends at zero
  // acceleration; joined, the plan speeds up and slows down through them. Measured (dev build):
  // 88.7 % and 92.9 % of the allowed length at ≥ 180 mm/s; the contour takes 3.517 and 3.456 s.
  const std::string text = gear_program();
  PlanOptions apart;
  apart.planner.join_runs = false;
  const Trajectory joined = test::plan_text(text), separate = test::plan_text(text, apart);
  test::expect_within_limits(separate, MotionLimits{});
  test::expect_continuous_junctions(separate, MotionLimits{});
  const GearShare with = gear_share(joined), without = gear_share(separate);
  EXPECT_LT(without.fast, 0.90 * without.allowed);
  EXPECT_GT(with.fast - without.fast, 0.03 * with.allowed);
  EXPECT_LT(gear_contour_s(joined), 0.99 * gear_contour_s(separate));
}

TEST(Contours, JoinedRunsKeepEveryLimitOnRandomWavyContours) {
  // Closed contours r(θ) = R·(1 + e·cos(mθ)) (rosettes, shallow to deeply lobed), flattened to chords
  // of 0.05-0.3 mm, 4 decimals, G64 P0.01, at 50-400 mm/s: where runs join, the plan still keeps the
  // speed, acceleration and jerk limits and every junction's velocity and acceleration steps, and
  // joining never makes a contour slower.
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int faster = 0, fitted_faster = 0;
  const int cases = test::random_cases(40);
  for (int c = 0; c < cases; ++c) {
    const double r_mm = 3.0 + 20.0 * unit(rng), e = 0.05 + 0.3 * unit(rng), chord_mm = 0.05 + 0.25 * unit(rng);
    const int lobes = 3 + static_cast<int>(9.0 * unit(rng));
    const double feed_mm_min = (50.0 + 350.0 * unit(rng)) * 60.0;
    const double length_mm = 2.0 * std::numbers::pi * r_mm * (1.0 + e);
    const int n = static_cast<int>(std::ceil(length_mm / chord_mm));
    std::string g = fmt::format("G21 G90\nG64 P0.01\nG0 X{:.4f} Y0\nM3 S500\nG1 F{:.1f}\n", 222.132 + r_mm * (1.0 + e),
                                feed_mm_min);
    for (int k = 1; k <= n; ++k) {
      const double t = 2.0 * std::numbers::pi * k / n, rad = r_mm * (1.0 + e * std::cos(lobes * t));
      g += fmt::format("X{:.4f} Y{:.4f}\n", 222.132 + rad * std::cos(t), rad * std::sin(t));
    }
    g += "M5\nM2\n";
    SCOPED_TRACE(fmt::format("case {}: R {:.2f} mm, e {:.3f}, {} lobes, chords {:.3f} mm, F {:.0f}", c, r_mm, e, lobes,
                             chord_mm, feed_mm_min));
    PlanOptions apart;
    apart.planner.join_runs = false;
    const Trajectory joined = test::plan_text(g), separate = test::plan_text(g, apart);
    test::expect_within_limits(joined, MotionLimits{});
    test::expect_continuous_junctions(joined, MotionLimits{});
    expect_sampled_within_limits(joined);
    EXPECT_LE(joined.duration_s(), separate.duration_s() * (1 + 1e-9));
    faster += joined.duration_s() < separate.duration_s() * (1 - 1e-3);
    // Fitted chords (--chords fit) keep the same limits and stay within P of the chords.
    PlanOptions fit;
    fit.planner.junction.fit_chords = true;
    const Trajectory fitted = test::plan_text(g, fit);
    test::expect_within_limits(fitted, MotionLimits{});
    test::expect_continuous_junctions(fitted, MotionLimits{});
    // Each piece against the chords of its own source line and the lines next to it (a bound on its
    // distance from the whole polyline).
    std::map<int, std::vector<Vec2>> chords;
    std::istringstream in(g);
    GcodeReader reader(in, "job.gcode");
    while (auto s = reader.next()) chords[s->line] = {s->start_m, s->end_m};
    double deviation = 0.0;
    for (const PlannedSegment& seg : fitted.segments()) {
      for (int m = 0; m <= 8; ++m) {
        const Vec2 p = evaluate(seg, seg.start_time_s + seg.duration_s * m / 8).position_m;
        double nearest = INFINITY;
        for (int line = seg.path.line - 1; line <= seg.path.line + 1; ++line) {
          if (chords.contains(line)) nearest = std::min(nearest, distance_to_polyline(p, chords[line]));
        }
        deviation = std::max(deviation, nearest);
      }
    }
    EXPECT_LE(deviation, 0.01e-3 * (1 + 1e-6));
    fitted_faster += fitted.duration_s() < joined.duration_s() * (1 - 1e-3);
  }
  EXPECT_GT(faster, cases / 3);
  // These chords come from equal steps of the angle, so they differ in length; fitting them takes
  // less time than blending them in more than half of the cases (measured: 23 of the 40, up to 32 % less; 11 take up
  // to 9 % longer).
  EXPECT_GT(fitted_faster, cases / 3);
}

TEST(Contours, FittedChordsStayWithinLimitsAndToleranceOnTheGear) {
  // --chords fit on the gear: the flanks' chains of chords become tangent biarcs through a curve
  // fitted to the vertices. Measured (dev build): 90.4 % of the allowed length at ≥ 180 mm/s against
  // 92.9 % blended, within 6.0 µm of the chords against 9.0 µm (P is 10 µm), and the contour takes
  // 3.693 s against 3.456 s: these chords are coarse for the curve (next to the root and tip fillets
  // they turn by 9-35° and the curvature changes fourfold from one vertex to the next), where the
  // fitted curve's biarcs swing more than the blender's corner arcs. Fitting pays on finer chords
  // (Contours.JoinedRunsKeepEveryLimitOnRandomWavyContours).
  const std::string text = gear_program();
  PlanOptions fit;
  fit.planner.junction.fit_chords = true;
  const Trajectory fitted = test::plan_text(text, fit), blended = test::plan_text(text);
  test::expect_within_limits(fitted, MotionLimits{});
  test::expect_continuous_junctions(fitted, MotionLimits{});
  expect_sampled_within_limits(fitted);
  const GearShare share = gear_share(fitted);
  EXPECT_GT(share.allowed, 0.150);
  EXPECT_GE(share.tip_fast, 0.99 * share.tip_allowed);
  EXPECT_GE(share.fast, 0.88 * share.allowed);
  EXPECT_LE(gear_deviation_m(fitted, text), 0.01e-3 * (1 + 1e-6));
  EXPECT_GT(fitted.segments().size(), blended.segments().size());  // about two pieces per chord
  EXPECT_LT(gear_contour_s(fitted), 1.10 * gear_contour_s(blended));
}

}  // namespace
}  // namespace stiffpath::motion
