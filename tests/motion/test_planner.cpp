// Planner property tests over seeded random programs: limits, continuity, G61 stops, and whole-program look-ahead.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <sstream>

#include "planner_checks.hpp"
#include "random_cases.hpp"
#include "random_program.hpp"
#include "stiffpath/motion/speed_change.hpp"

namespace stiffpath::motion {
namespace {

using test::plan_text;

TEST(PlannerRandom, EveryProgramStaysWithinLimitsAndJoinsContinuously) {
  std::mt19937_64 rng(99);
  const int programs = std::max(4, test::random_cases(400) / 10);
  for (int p = 0; p < programs; ++p) {
    const std::string gcode = test::random_program(rng, 60);
    PlanOptions options;
    options.limits.max_acceleration_m_s2 = 5 + 60 * (p % 7) / 6.0;   // 5 … 65 m/s²
    options.limits.max_jerk_m_s3 = options.limits.max_acceleration_m_s2 / (0.002 + 0.002 * (p % 5));
    const Trajectory trajectory = plan_text(gcode, options);
    SCOPED_TRACE("program " + std::to_string(p) + ":\n" + gcode);
    ASSERT_FALSE(trajectory.empty());
    test::expect_within_limits(trajectory, options.limits);
    test::expect_continuous_junctions(trajectory, options.limits);
    if (HasFatalFailure()) return;
  }
}

std::vector<PathSegment> programmed_segments(const std::string& gcode) {
  std::istringstream in(gcode);
  GcodeReader reader(in, "job.gcode");
  std::vector<PathSegment> segs;
  while (auto s = reader.next()) segs.push_back(*s);
  return segs;
}

TEST(PlannerRandom, ExactStopProgramsPassEveryProgrammedPointAndEndAtRest) {
  std::mt19937_64 rng(23);
  for (int p = 0; p < std::max(4, test::random_cases(400) / 20); ++p) {
    std::string gcode = "G61\n" + test::random_program(rng, 60);  // before the program's first mode too
    for (std::size_t at = gcode.find("G64"); at != std::string::npos; at = gcode.find("G64", at)) {
      gcode.replace(at, gcode.find('\n', at) - at, "G61");  // no blending anywhere
    }
    const std::vector<PathSegment> programmed = programmed_segments(gcode);
    const Trajectory trajectory = test::plan_text(gcode);
    ASSERT_EQ(trajectory.segments().size(), programmed.size()) << "program " << p;
    for (std::size_t i = 0; i < programmed.size(); ++i) {
      const auto& seg = trajectory.segments()[i];
      ASSERT_EQ(trajectory.evaluate(seg.end_time_s()).position_m, programmed[i].end_m) << "program " << p << " line " << seg.path.line;
    }
    const TrajectorySample last = trajectory.evaluate(trajectory.duration_s());
    EXPECT_EQ(last.position_m, programmed.back().end_m);
    EXPECT_EQ(last.velocity_m_s, Vec2::Zero());
    EXPECT_EQ(last.acceleration_m_s2, Vec2::Zero());
  }
}

// The reference: whole-program look-ahead written out plainly (all runs, all junction limits, a full
// backward pass, a forward pass) on the same segments, gathered into runs by the same rule.
struct ReferenceRun {
  double length_m = 0.0, entry_limit_m_s = 0.0;
  SegmentLimits limits, high;  // the lowest and the highest of its segments' limits
  bool dwell = false;
  std::size_t segments = 0;
  PathSegment first, last;  // its first and last segment
};

std::vector<ReferenceRun> reference_runs(const std::string& gcode, const PlanOptions& options) {
  std::istringstream in(gcode);
  GcodeReader reader(in, "job.gcode", options.gcode);
  LineMerger merger(reader);
  const std::unique_ptr<CornerBlender> blender = make_blender(merger, options);  // the path stages of a plan
  std::vector<ReferenceRun> runs;
  std::optional<Run> open;
  PathSegment previous;
  SegmentLimits previous_limits;
  double previous_cap = 0.0;
  while (auto s = blender->next()) {
    if (s->kind != SegmentKind::dwell && !(s->length_m > 0.0)) continue;
    const SegmentLimits lim = segment_limits(*s, options.limits);
    if (open && extend_run(*open, previous, previous_limits, *s, lim, options.limits, options.planner.junction,
                           options.planner.runs)) {
      ++runs.back().segments;
      runs.back().last = *s;
    } else {
      if (open) {
        runs.back().length_m = open->length_m;
        runs.back().limits = open->low;
        runs.back().high = open->high;
        runs.back().entry_limit_m_s = std::min({runs.back().entry_limit_m_s, open->low.max_velocity_m_s, previous_cap});
        previous_cap = runs.back().dwell ? 0.0 : open->low.max_velocity_m_s;
      }
      const double junction = runs.empty() ? 0.0
                                           : junction_speed_limit(previous, previous_limits, *s, lim, options.limits,
                                                                  options.planner.junction);
      runs.push_back({0.0, junction, lim, lim, s->kind == SegmentKind::dwell, 1, *s, *s});
      open = start_run(*s, lim, options.planner.runs);
    }
    previous = *s;
    previous_limits = lim;
  }
  if (open) {
    runs.back().length_m = open->length_m;
    runs.back().limits = open->low;
    runs.back().high = open->high;
    runs.back().entry_limit_m_s = std::min({runs.back().entry_limit_m_s, open->low.max_velocity_m_s, previous_cap});
  }
  return runs;
}

// Runs that share one profile, with its entry and exit speed.
struct ReferenceProfile {
  std::size_t runs = 0;
  double entry_m_s = 0.0, exit_m_s = 0.0;
};

// A full backward pass, then a forward pass in which, once a profile's entry is known, the runs
// after it join it while their junction is tangent, the limits stay within the run bands, the
// entry admits the joined length, and the profile cannot reach any junction's bound (from the entry
// forward or from the exit back).
std::vector<ReferenceProfile> reference_profiles(const std::vector<ReferenceRun>& runs, const PlanOptions& options) {
  const std::size_t n = runs.size();
  std::vector<double> entry_max(n + 1, 0.0);  // entry_max[n]: the end of the program, at rest
  for (std::size_t i = n; i-- > 0;) {
    const auto& l = runs[i].limits;
    const double braking =
        runs[i].dwell ? 0.0 : max_entry_speed(runs[i].length_m, entry_max[i + 1], l.max_acceleration_m_s2, l.max_jerk_m_s3);
    entry_max[i] = std::min(runs[i].entry_limit_m_s, braking);
  }
  const RunRules& rules = options.planner.runs;
  std::vector<ReferenceProfile> profiles;
  double v0 = 0.0;
  for (std::size_t i = 0; i < n;) {
    double length = runs[i].length_m;
    SegmentLimits low = runs[i].limits, high = runs[i].high;
    std::size_t segments = runs[i].segments, k = i + 1;
    std::vector<std::pair<double, double>> junctions;
    double exit_bound = entry_max[i + 1];
    while (!runs[i].dwell && options.planner.one_profile_per_run && options.planner.join_runs && k < n && !runs[k].dwell &&
           k - i < rules.max_joined_runs && segments + runs[k].segments <= rules.max_segments) {
      const SegmentLimits joined = lower_limits(low, runs[k].limits), joined_high = higher_limits(high, runs[k].high);
      if (!within_run_bands(joined, joined_high, rules) || v0 > joined.max_velocity_m_s) break;
      const double a = joined.max_acceleration_m_s2, j = joined.max_jerk_m_s3;
      const PathSegment& last = runs[k - 1].last;
      const PathSegment& first = runs[k].first;
      const double bound = tangent_junction_speed_limit(last, segment_limits(last, options.limits), first,
                                                        segment_limits(first, options.limits), options.limits,
                                                        options.planner.junction, a);
      if (!(bound > 0.0)) break;
      const double joined_length = length + runs[k].length_m;
      const double after = std::min(entry_max[k + 1], joined.max_velocity_m_s);
      if (v0 > max_entry_speed(joined_length, after, a, j)) break;
      const double exit = max_exit_speed(joined_length, v0, after, a, j);
      junctions.emplace_back(length, bound);
      bool below = true;
      for (const auto& [at, limit] : junctions) {
        below = below && std::min(fastest_speed_up(at, v0, a, j), fastest_speed_up(joined_length - at, exit, a, j)) *
                                 (1.0 + 1e-9) <= limit;
      }
      if (!below) break;
      length = joined_length;
      low = joined;
      high = joined_high;
      exit_bound = after;
      segments += runs[k].segments;
      ++k;
    }
    const double exit = runs[i].dwell ? 0.0
                                      : max_exit_speed(length, v0, exit_bound, low.max_acceleration_m_s2, low.max_jerk_m_s3);
    profiles.push_back({k - i, v0, exit});
    v0 = exit;
    i = k;
  }
  return profiles;
}

TEST(PlannerRandom, StreamedPlanEqualsWholeProgramLookAhead) {
  std::mt19937_64 rng(5);
  std::size_t joined = 0, joined_runs = 0;
  for (int p = 0; p < std::max(4, test::random_cases(400) / 20); ++p) {
    const std::string gcode = test::random_program(rng, 80);
    for (const bool runs : {true, false}) {
      PlanOptions options;
      options.planner.one_profile_per_run = runs;
      if (!runs) options.planner.runs.max_segments = 1;  // the reference groups by the same rules
      const Trajectory trajectory = plan_text(gcode, options);
      const std::vector<ReferenceRun> reference_runs_of_program = reference_runs(gcode, options);
      const std::vector<ReferenceProfile> reference = reference_profiles(reference_runs_of_program, options);
      std::size_t segment = 0, run = 0;
      for (std::size_t r = 0; r < reference.size(); ++r) {
        ASSERT_LT(segment, trajectory.segments().size());
        ASSERT_EQ(trajectory.segments()[segment].entry_speed_m_s, reference[r].entry_m_s) << "program " << p << " profile " << r;
        std::size_t segments = 0;
        for (std::size_t k = 0; k < reference[r].runs; ++k) segments += reference_runs_of_program[run + k].segments;
        // One profile: every segment of it carries the same profile, and the next one starts anew.
        ASSERT_EQ(trajectory.segments()[segment].profile_offset_s, 0.0);
        for (std::size_t k = 1; k < segments; ++k) {
          ASSERT_EQ(trajectory.segments()[segment + k].profile.duration_s, trajectory.segments()[segment].profile.duration_s);
          ASSERT_GT(trajectory.segments()[segment + k].profile_offset_s, 0.0);
        }
        segment += segments;
        ASSERT_EQ(trajectory.segments()[segment - 1].exit_speed_m_s, reference[r].exit_m_s) << "program " << p << " profile " << r;
        joined += runs ? segments - 1 : 0;
        joined_runs += reference[r].runs - 1;
        run += reference[r].runs;
      }
      ASSERT_EQ(run, reference_runs_of_program.size());
      ASSERT_EQ(segment, trajectory.segments().size());
    }
  }
  EXPECT_GT(joined, 0u);       // the random programs do have tangent runs
  EXPECT_GT(joined_runs, 0u);  // … and runs that join the profile before them
}

TEST(PlannerRandom, BoundedWindowStaysFeasibleAndIsNeverFaster) {
  // A full window closes runs early, so with runs the two plans differ in how segments share
  // profiles; the bounded one must still be feasible. With one profile per segment each of its
  // junction speeds is at most the whole-program one where every segment is long enough for any
  // speed between 0 and its entry at its exit, as blended chords are. Fitted chords leave short
  // pieces next to a corner's fillet, across which the exits reachable from an entry are not one
  // interval: from 64.7 mm/s a 166 µm piece can end at rest but not at 2.9 mm/s (a stop takes
  // v^1.5/sqrt(j), slowing to v1 (v + v1)·sqrt((v − v1)/j), longer); the whole-program plan enters
  // faster and stops, the window enters slower and goes on. There only the feasibility and the
  // total time are compared.
  std::mt19937_64 rng(17);
  for (int p = 0; p < 6; ++p) {
    const std::string gcode = test::random_program(rng, 80);
    for (const bool runs : {true, false}) {
      for (const bool fit : {false, true}) {
        SCOPED_TRACE(fit ? "chords fitted" : "chords blended");
        PlanOptions whole, bounded;
        whole.planner.one_profile_per_run = bounded.planner.one_profile_per_run = runs;
        whole.planner.junction.fit_chords = bounded.planner.junction.fit_chords = fit;
        bounded.planner.max_lookahead_segments = 3;
        const Trajectory exact = plan_text(gcode, whole), windowed = plan_text(gcode, bounded);
        test::expect_within_limits(windowed, bounded.limits);
        test::expect_continuous_junctions(windowed, bounded.limits);
        ASSERT_EQ(exact.segments().size(), windowed.segments().size());
        if (runs) continue;
        EXPECT_GE(windowed.duration_s(), exact.duration_s() * (1 - 1e-12));
        if (fit) continue;
        for (std::size_t i = 0; i < exact.segments().size(); ++i) {
          EXPECT_LE(windowed.segments()[i].exit_speed_m_s, exact.segments()[i].exit_speed_m_s * (1 + 1e-12));
        }
      }
    }
  }
}

TEST(PlannerRandom, AnalyticDerivativesMatchFiniteDifferencesOnLinesAndArcs) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Trajectory trajectory = plan_text(test::random_program(rng, 120));
  const double eps = std::numeric_limits<double>::epsilon();
  int arcs = 0;
  for (const auto& seg : trajectory.segments()) {
    // Differences over steps near the resolution of the program clock (ulp(t) ≈ 1e-16 s) say nothing.
    if (seg.path.kind == SegmentKind::dwell || seg.duration_s < 1e-6) continue;
    arcs += seg.path.kind == SegmentKind::arc;
    const double h = 1e-4 * seg.duration_s, t = seg.start_time_s + 2 * h + (seg.duration_s - 4 * h) * unit(rng);
    const TrajectorySample m = evaluate(seg, t - h), z = evaluate(seg, t), q = evaluate(seg, t + h);
    const MotionLimits lim;
    const double pos_scale = z.position_m.norm(), vel_scale = 2.0, acc_scale = lim.max_acceleration_m_s2;
    EXPECT_LT(((q.position_m - m.position_m) / (2 * h) - z.velocity_m_s).norm(),
              lim.max_acceleration_m_s2 * h + 8 * eps * pos_scale / h) << "line " << seg.path.line;
    EXPECT_LT(((q.velocity_m_s - m.velocity_m_s) / (2 * h) - z.acceleration_m_s2).norm(),
              lim.max_jerk_m_s3 * h + 8 * eps * vel_scale / h + 1e-9) << "line " << seg.path.line;
    // The profile's jerk switches between phases; compare where no phase boundary lies within ±h.
    bool switch_nearby = false;
    double boundary = seg.start_time_s - seg.profile_offset_s;
    for (const double phase : seg.profile.phase_s) {
      boundary += phase;
      switch_nearby = switch_nearby || std::abs(boundary - t) <= 1.01 * h;
    }
    if (!switch_nearby) {
      EXPECT_LT(((q.acceleration_m_s2 - m.acceleration_m_s2) / (2 * h) - z.jerk_m_s3).norm(),
                1e-3 * lim.max_jerk_m_s3 + 8 * eps * acc_scale / h) << "line " << seg.path.line;
    }
  }
  EXPECT_GT(arcs, 10);
}

}  // namespace
}  // namespace stiffpath::motion
