// Streaming simulation: strokes partition the mark, RunMeter sums them, refuses line metrics where a stroke is not a line.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <sstream>

#include "stiffpath/core/error.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::simulation {
namespace {

// The uncompensated joint stream of a G-code program on the thesis robot at 2 g (IK of each 2 kHz sample).
std::vector<compensation::JointCommand> joints_of(const std::string& gcode, double acceleration_g = 2) {
  const auto five_bar = kinematics::load_robot("oc-gu").five_bar();
  motion::PlanOptions plan;
  plan.limits.max_acceleration_m_s2 = acceleration_g * 9.80665;
  plan.limits.max_jerk_m_s3 = motion::default_jerk_m_s3(plan.limits.max_acceleration_m_s2);
  std::istringstream program(gcode);
  motion::TrajectoryStream stream(program, "test", plan);
  std::vector<compensation::JointCommand> out;
  while (const auto s = stream.next()) {
    compensation::JointCommand c;
    c.t_s = s->t_s;
    c.q_rad = five_bar.inverse(s->position_m);
    c.qd_rad_s = five_bar.jacobian(c.q_rad).inverse() * s->velocity_m_s;
    c.target_m = s->position_m;
    c.laser_on = s->laser_on;
    out.push_back(c);
  }
  return out;
}

JointSource source_of(const std::vector<compensation::JointCommand>& joints) {
  return [&joints, i = std::size_t{0}]() mutable -> std::optional<compensation::JointCommand> {
    if (i == joints.size()) return std::nullopt;
    return joints[i++];
  };
}

// The uncompensated job of `gcode` on the thesis robot's twin, each stroke measured by `meter`; the totals.
RunMetrics metered(const std::string& gcode, RunMeter& meter) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto joints = joints_of(gcode);
  return meter.totals(simulate(source_of(joints), robot, make_true_compliance(robot), {}, meter.sink()));
}

// Two lines of 40 and 30 mm with a travel move between (G61: exact stops, so each is one straight stroke).
const char* kTwoLines =
    "G21 G90 G61\nG0 X190 Y-40\nM3 S1000\nG1 X230 Y-40 F60000\nM5\nG0 X200 Y20\nM3 S1000\nG1 X200 Y50\nM5\nM2\n";

TEST(Strokes, StrokesPartitionTheWholeMark) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto truth = make_true_compliance(robot);
  const auto joints = joints_of(kTwoLines);
  std::vector<Stroke> strokes;
  const SimulationResult streamed =
      simulate(source_of(joints), robot, truth, {}, [&](const Stroke& s) { strokes.push_back(s); });
  const SimulationResult whole = simulate(source_of(joints), robot, truth);
  EXPECT_TRUE(streamed.marked.empty());
  ASSERT_EQ(strokes.size(), 2U);
  EXPECT_EQ(streamed.strokes, 2U);
  EXPECT_EQ(streamed.peak_deflection_m, whole.peak_deflection_m);
  std::vector<Vec2> marked, commanded;
  for (std::size_t k = 0; k < strokes.size(); ++k) {
    EXPECT_EQ(strokes[k].index, k);
    EXPECT_LT(strokes[k].start_s, strokes[k].end_s);
    marked.insert(marked.end(), strokes[k].marked.begin(), strokes[k].marked.end());
    commanded.insert(commanded.end(), strokes[k].commanded.begin(), strokes[k].commanded.end());
  }
  EXPECT_LT(strokes[0].end_s, strokes[1].start_s);
  EXPECT_EQ(marked, whole.marked);
  EXPECT_EQ(commanded, whole.commanded);
  // Each stroke's command runs from its line's start to its end (mm in the G-code), up to the distance
  // covered within one 0.5 ms sample of a jerk-limited start (j·Δt³/6 ≈ 0.08 µm at 2 g).
  EXPECT_NEAR((strokes[0].commanded.front() - Vec2(0.190, -0.040)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((strokes[0].commanded.back() - Vec2(0.230, -0.040)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((strokes[1].commanded.front() - Vec2(0.200, 0.020)).norm(), 0.0, 1e-6);
  EXPECT_NEAR((strokes[1].commanded.back() - Vec2(0.200, 0.050)).norm(), 0.0, 1e-6);
}

TEST(Strokes, MeterSumsLengthsAndTakesTheLargestDeviations) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto truth = make_true_compliance(robot);
  const auto joints = joints_of(kTwoLines);
  RunMeter meter(1);
  const SimulationResult run = simulate(source_of(joints), robot, truth, {}, meter.sink());
  const RunMetrics total = meter.totals(run);
  ASSERT_EQ(meter.strokes().size(), 2U);
  const RunMetrics& a = meter.strokes()[0].metrics;
  const RunMetrics& b = meter.strokes()[1].metrics;
  EXPECT_NEAR(a.commanded_length_m, 0.040, 1e-7);
  EXPECT_NEAR(b.commanded_length_m, 0.030, 1e-7);
  EXPECT_NEAR(total.commanded_length_m, 0.070, 2e-7);
  EXPECT_NEAR(total.length_m, a.length_m + b.length_m, 1e-15);
  EXPECT_NEAR(total.length_m, 0.070, 0.5e-3);  // the mark of an exact-stop line: within the tip's deflection
  EXPECT_EQ(total.max_deviation_m, std::max(a.max_deviation_m, b.max_deviation_m));
  EXPECT_EQ(total.path_accuracy_m, std::max(a.path_accuracy_m, b.path_accuracy_m));
  EXPECT_EQ(total.strokes, 2U);
  EXPECT_EQ(total.line_strokes, 2U);
  EXPECT_EQ(total.corners, 0U);
  EXPECT_EQ(total.peak_deflection_m, run.peak_deflection_m);
}

// One stroke: the meter's totals are measure_run's numbers on the whole mark.
TEST(Strokes, OneStrokeJobGivesMeasureRunsNumbers) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto truth = make_true_compliance(robot);
  const auto joints = joints_of(
      "G21 G90 G61\nG0 X187.132 Y-60\nM3 S1000\nG1 X257.132 Y-60 F120000\nG1 X222.132 Y60\nG1 X187.132 Y-60\nM5\n");
  RunMeter meter(3);
  const RunMetrics streamed = meter.totals(simulate(source_of(joints), robot, truth, {}, meter.sink()));
  const RunMetrics whole = measure_run(simulate(source_of(joints), robot, truth), 3);
  EXPECT_EQ(streamed.length_m, whole.length_m);
  EXPECT_EQ(streamed.length_error_m, whole.length_error_m);
  EXPECT_EQ(streamed.deviation_area_m2, whole.deviation_area_m2);
  EXPECT_EQ(streamed.max_deviation_m, whole.max_deviation_m);
  EXPECT_EQ(streamed.path_accuracy_m, whole.path_accuracy_m);
  EXPECT_EQ(streamed.corners, 2U);  // the triangle's two interior exact stops
  EXPECT_EQ(streamed.cornering_round_off_m, whole.cornering_round_off_m);
  EXPECT_EQ(streamed.cornering_overshoot_m, whole.cornering_overshoot_m);
  EXPECT_EQ(streamed.residual_vibration_m, whole.residual_vibration_m);
}

// With --sides 3 a straight line cannot be three sides: its line metrics are refused with the reason,
// the triangle's are kept, and the totals are the triangle's alone.
TEST(Strokes, AStrokeThatIsNotTheGivenShapeIsRefusedNotMeasured) {
  RunMeter meter(3);
  const RunMetrics total = metered(
      "G21 G90 G61\nG0 X187.132 Y-60\nM3 S1000\nG1 X257.132 Y-60 F120000\nG1 X222.132 Y60\nG1 X187.132 Y-60\nM5\n"
      "G0 X190 Y40\nM3 S1000\nG1 X230 Y40\nM5\n",
      meter);
  ASSERT_EQ(meter.strokes().size(), 2U);
  EXPECT_TRUE(meter.strokes()[0].refusal.empty()) << meter.strokes()[0].refusal;
  EXPECT_NE(meter.strokes()[1].refusal.find("not 3 straight sides"), std::string::npos) << meter.strokes()[1].refusal;
  EXPECT_EQ(total.line_strokes, 1U);
  EXPECT_EQ(total.length_m, meter.strokes()[0].metrics.length_m);
  EXPECT_TRUE(meter.strokes()[1].path_accuracy);  // AT_p needs no sides
}

// Without a number of sides each stroke is measured as its command's sharp corners plus one: the
// triangle as three sides (closed), the line as one, with the numbers --sides would give each.
TEST(Strokes, SidesAreInferredFromEachStrokesCorners) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto truth = make_true_compliance(robot);
  const auto joints = joints_of(
      "G21 G90 G61\nG0 X187.132 Y-60\nM3 S1000\nG1 X257.132 Y-60 F120000\nG1 X222.132 Y60\nG1 X187.132 Y-60\nM5\n"
      "G0 X190 Y40\nM3 S1000\nG1 X230 Y40\nM5\n");
  RunMeter inferred(0), triangle(3), line(1);
  (void)simulate(source_of(joints), robot, truth, {}, [&](const Stroke& s) {
    inferred.add(s);
    triangle.add(s);
    line.add(s);
  });
  ASSERT_EQ(inferred.strokes().size(), 2U);
  EXPECT_EQ(inferred.strokes()[0].sides, 3);
  EXPECT_EQ(inferred.strokes()[1].sides, 1);
  EXPECT_EQ(inferred.strokes()[0].metrics.length_m, triangle.strokes()[0].metrics.length_m);
  EXPECT_EQ(inferred.strokes()[0].metrics.max_deviation_m, triangle.strokes()[0].metrics.max_deviation_m);
  EXPECT_EQ(inferred.strokes()[1].metrics.length_m, line.strokes()[1].metrics.length_m);
  // The triangle's perimeter: 70 + 2·√(35² + 120²) = 320 mm.
  EXPECT_NEAR(inferred.strokes()[0].metrics.commanded_length_m, 0.070 + 2 * std::hypot(0.035, 0.120), 5e-6);
}

// A contour that is no straight sides (a G2 circle: no sharp corners, so one inferred side) gets no line
// metrics: read as one side it would report its own shape as the robot's deviation. The straight line
// after it keeps its numbers, and every stroke keeps AT_p.
TEST(Strokes, AContourThatIsNotStraightSidesGetsNoLineMetrics) {
  RunMeter meter(0);
  const RunMetrics total = metered(
      "G21 G90 G61\nG0 X202.132 Y0\nM3 S1000\nG2 X202.132 Y0 I20 J0 F60000\nM5\nG0 X190 Y40\nM3 S1000\nG1 X230 Y40\nM5\n",
      meter);
  ASSERT_EQ(meter.strokes().size(), 2U);
  EXPECT_NE(meter.strokes()[0].refusal.find("the command itself lies up to"), std::string::npos)
      << meter.strokes()[0].refusal;
  EXPECT_EQ(meter.strokes()[0].sides, 0);
  EXPECT_TRUE(meter.strokes()[0].path_accuracy);
  EXPECT_TRUE(meter.strokes()[1].refusal.empty()) << meter.strokes()[1].refusal;
  EXPECT_EQ(total.line_strokes, 1U);
  EXPECT_NEAR(total.commanded_length_m, 0.040, 5e-6);  // only the line's length is summed
}

// A hatch of `lines` lines of 8 mm along x, 40 µm apart, joined by 40 µm steps in y (G61: exact stops).
std::string hatch(int lines, std::vector<Vec2>& starts, std::vector<Vec2>& ends) {
  std::string g = "G21 G90 G61\nG0 X190 Y-10\nM3 S1000\n";
  double x = 190.0;
  for (int k = 0; k < lines; ++k) {
    const double y = -10.0 + 0.04 * k;
    if (k > 0) g += fmt::format("G1 X{:.3f} Y{:.3f} F120000\n", x, y);
    starts.emplace_back(x * 1e-3, y * 1e-3);
    x = x == 190.0 ? 198.0 : 190.0;
    g += fmt::format("G1 X{:.3f} Y{:.3f} F120000\n", x, y);
    ends.emplace_back(x * 1e-3, y * 1e-3);
  }
  return g + "M5\nM2\n";
}

// The oracle of a long stroke: a hatch marked as one stroke (its turns marked too) measures, line by
// line, as the very same motion marked with the laser off on the turns, each line a stroke of its own
// that is measured alone (one side, no corners, no chain). The one stroke is cut at the command's
// corners; each line's own stroke runs from the sample nearest its start to the one nearest its end.
TEST(Strokes, AHatchMarkedAsOneStrokeMeasuresAsItsLinesMarkedOneByOne) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto truth = make_true_compliance(robot);
  std::vector<Vec2> starts, ends;
  const int lines = 12;
  const auto one = joints_of(hatch(lines, starts, ends), 5);
  auto apart = one;
  std::optional<std::size_t> first_on;
  std::size_t last_on = 0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    if (one[i].laser_on && !first_on) first_on = i;
    if (one[i].laser_on) last_on = i;
  }
  ASSERT_TRUE(first_on.has_value());
  const auto nearest = [&](const Vec2& p) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < one.size(); ++i) best = (one[i].target_m - p).norm() < (one[best].target_m - p).norm() ? i : best;
    return best;
  };
  for (auto& c : apart) c.laser_on = false;
  for (int k = 0; k < lines; ++k) {
    const std::size_t from = k == 0 ? *first_on : nearest(starts[k]);
    const std::size_t to = k == lines - 1 ? last_on + 1 : nearest(ends[k]);
    for (std::size_t i = from; i < to; ++i) apart[i].laser_on = true;
  }
  RunMeter whole(0), each(0);
  const auto run = simulate(source_of(one), robot, truth, {}, static_cast<StrokeObserver&>(whole));
  (void)simulate(source_of(apart), robot, truth, {}, static_cast<StrokeObserver&>(each));
  ASSERT_EQ(whole.stroke_count(), 1u);
  ASSERT_EQ(each.stroke_count(), static_cast<std::size_t>(lines));
  const StrokeMetrics& s = whole.strokes()[0];
  ASSERT_TRUE(s.refusal.empty()) << s.refusal;
  EXPECT_EQ(s.sides, lines);
  EXPECT_EQ(s.metrics.corners, static_cast<std::size_t>(lines - 1));  // the turns: reversals, no line corners
  for (const auto& line : each.strokes()) {
    ASSERT_TRUE(line.refusal.empty()) << line.refusal;
    EXPECT_EQ(line.sides, 1);
    EXPECT_EQ(line.metrics.corners, 0u);
  }
  const RunMetrics a = whole.totals(run), b = each.totals(run);
  EXPECT_NEAR(a.length_m, b.length_m, 1e-12 * b.length_m);
  EXPECT_NEAR(a.commanded_length_m, b.commanded_length_m, 1e-12 * b.commanded_length_m);
  EXPECT_NEAR(a.deviation_area_m2, b.deviation_area_m2, 1e-12 * b.deviation_area_m2);
  EXPECT_EQ(a.max_deviation_m, b.max_deviation_m);
  EXPECT_EQ(a.path_accuracy_m, b.path_accuracy_m);
  // and those are the hatch's: 8 mm lines, ending where their exact stops put them.
  EXPECT_NEAR(b.commanded_length_m, lines * 0.008, lines * 1e-6);
  EXPECT_GT(a.max_deviation_m, 1e-6);
  EXPECT_LT(a.cornering_round_off_m, 0.1e-3);  // every turn reached: CR is µm, not the metres of a runaway corner
}

// Joint commands the robot cannot take are refused at the record, with the value and the limit.
TEST(Strokes, JointCommandsBeyondTheRobotAreRefusedAtTheirRecord) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto truth = make_true_compliance(robot);
  auto joints = joints_of(kTwoLines);
  auto beyond = joints;
  beyond[40].q_rad[0] = robot.joints[0].max_rad + 0.1;
  try {
    (void)simulate(source_of(beyond), robot, truth);
    FAIL() << "a joint beyond its limit was simulated";
  } catch (const RecordRefused& e) {
    EXPECT_EQ(e.record(), 40u);
    const double deg = (robot.joints[0].max_rad + 0.1) * 180 / std::numbers::pi;
    EXPECT_NE(e.message().find(fmt::format("{:.3f} deg", deg)), std::string::npos) << e.message();
    EXPECT_NE(e.message().find(fmt::format("upper limit of {:.3f} deg", robot.joints[0].max_rad * 180 / std::numbers::pi)),
              std::string::npos)
        << e.message();
  }
  // The thesis robot's tip is l·(e^{iθ1} + e^{iθ2}): (30°, −30°) and (−30°, 30°), both within the limits,
  // put it on the same point, the second in the other working mode (the arms folded through each other).
  const double a = 30 * std::numbers::pi / 180;
  ASSERT_LT((robot.five_bar().inverse(robot.five_bar().forward(Vec2{a, -a})) - Vec2{a, -a}).norm(), 1e-9);
  auto swapped = joints;
  swapped[25].q_rad = {-a, a};
  try {
    (void)simulate(source_of(swapped), robot, truth);
    FAIL() << "a command in the other working mode was simulated";
  } catch (const RecordRefused& e) {
    EXPECT_EQ(e.record(), 25u);
    EXPECT_NE(e.message().find("another working mode"), std::string::npos) << e.message();
  }
  // The work budget: refused at the record that would take the job beyond it, before stepping it.
  SimulationOptions small;
  small.max_steps = 5000;
  try {
    (void)simulate(source_of(joints), robot, truth, small);
    FAIL() << "the work budget was not enforced";
  } catch (const RecordRefused& e) {
    EXPECT_NE(e.message().find("work budget of 5000 integration steps"), std::string::npos) << e.message();
    EXPECT_LE(e.record() * 10 + 2000, 5000u + 10);  // 10 steps per 0.5 ms record, the settling's 2000 counted first
  }
}

TEST(Strokes, AJobThatNeverFiresTheLaserHasNothingToMeasure) {
  const auto robot = kinematics::load_robot("oc-gu");
  const auto joints = joints_of("G21 G90\nG0 X190 Y-40\nG1 X230 Y-40 F60000\n");
  RunMeter meter(1);
  const auto run = simulate(source_of(joints), robot, make_true_compliance(robot), {}, meter.sink());
  EXPECT_EQ(run.strokes, 0U);
  EXPECT_THROW((void)meter.totals(run), Error);
}

}  // namespace
}  // namespace stiffpath::simulation
