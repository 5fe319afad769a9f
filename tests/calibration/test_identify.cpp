// The identification recovers known tip parameters from marks made with them, and says what it cannot tell.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "kept_commands.hpp"
#include "stiffpath/job/prepared_job.hpp"

namespace stiffpath::calibration {
namespace {

struct Marked {
  kinematics::Robot robot;
  std::shared_ptr<compliance::Model> model;
  PlateDesign plate;
  std::vector<compensation::JointCommand> commands;
};

// The plate for oc-gu, planned and compensated by the default job, as a user's `run` would make its joint file.
const Marked& marked() {
  static const Marked m = [] {
    Marked out;
    out.robot = kinematics::load_robot("oc-gu");
    out.model = std::shared_ptr<compliance::Model>(compliance::load_robot_model(out.robot).model.release());
    out.plate = design_plate(out.robot, compliance::table_region(compliance::robot_table(out.robot)));
    job::JobSpec spec = job::default_job(out.robot);
    spec.model.given = out.model;
    test::Keep keep;
    job::run(job::prepare(spec, job::Program::text(plate_gcode(out.plate), "plate.gcode")), &keep);
    out.commands = std::move(keep.commands);
    return out;
  }();
  return m;
}

// What the scan would show of the plate's strokes if the tip behaved as `truth` says, with centre-line noise.
std::vector<ObservedMark> observe(const Marked& m, const TipParameters& truth, double noise_m, std::uint64_t seed) {
  const auto predicted = predict_marks(m.commands, m.robot, *m.model, truth);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<ObservedMark> out;
  for (const auto& stroke : m.plate.strokes) {
    for (const auto& p : predicted) {
      // (A timing stroke's laser switches at the first 2 kHz sample past its start: up to a sample's travel on.)
      if ((p.commanded_start_m - stroke.start_m).norm() > 0.5e-3) continue;
      ObservedMark o{stroke.id, {}};
      // One centre-line point per 21 µm of the mark, as a 1200 dpi scan gives about one per pixel.
      double since = 1e9;
      for (std::size_t k = 0; k < p.points_m.size(); ++k) {
        if (k > 0) since += (p.points_m[k] - p.points_m[k - 1]).norm();
        if (since < 21e-6 && k + 1 < p.points_m.size()) continue;
        since = 0.0;
        o.points_m.push_back(p.points_m[k] + Vec2(noise(rng), noise(rng)));
      }
      out.push_back(std::move(o));
    }
  }
  return out;
}

TEST(Identify, TheMarksOfTheRobotAsItIsFitWithNoChange) {
  const Marked& m = marked();
  TipParameters same;
  same.damping_ratio = m.robot.tip_damping_ratio;
  const auto area = m.plate.area;
  same.correction.origin_m = {0.5 * (area.x_min + area.x_max), 0.5 * (area.y_min + area.y_max)};
  same.correction.half_size_m = {0.5 * (area.x_max - area.x_min), 0.5 * (area.y_max - area.y_min)};
  const Identification id = identify(m.commands, m.robot, *m.model, m.plate, observe(m, same, 0.0, 1));
  EXPECT_LT(id.rms_before_m, 1e-7);
  for (const auto& v : id.values) EXPECT_NEAR(v.after, v.before, 1e-3 * std::max(1.0, std::abs(v.before))) << v.name;
}

TEST(Identify, RecoversTheTipItWasMarkedWithWithinItsUncertainty) {
  const Marked& m = marked();
  TipParameters truth;
  const auto area = m.plate.area;
  truth.correction.origin_m = {0.5 * (area.x_min + area.x_max), 0.5 * (area.y_min + area.y_max)};
  truth.correction.half_size_m = {0.5 * (area.x_max - area.x_min), 0.5 * (area.y_max - area.y_min)};
  truth.correction.sx = {1.12, 0.05, -0.03};  // 12 % more deflection along x, varying over the plate
  truth.correction.sy = {0.92, -0.04, 0.06};
  truth.correction.sxy = {0.04, -0.02, 0.01};  // the principal directions turned, more on the left
  truth.damping_ratio = 2.0 * m.robot.tip_damping_ratio;
  truth.frequency_scale = 1.05;
  truth.laser_on_delay_s = 0.8e-3;
  truth.laser_off_delay_s = -1.5e-3;
  const double noise = 2e-6;
  const Identification id = identify(m.commands, m.robot, *m.model, m.plate, observe(m, truth, noise, 7));
  std::printf("%s after %d iterations, rms %.3g -> %.3g m\n", core::to_string(id.stop), id.iterations, id.rms_before_m,
              id.rms_after_m);
  for (const auto& v : id.values) {
    std::printf("  %-18s %g -> %g +- %g%s\n", v.name.c_str(), v.before, v.after, v.sigma, v.determined ? "" : " (held)");
  }
  // The fit explains the marks down to their noise, where before it missed them by tens of µm.
  EXPECT_GT(id.rms_before_m, 5e-6);
  EXPECT_LT(id.rms_after_m, 1.5 * noise);
  const double want[] = {truth.correction.sx[0], truth.correction.sx[1], truth.correction.sx[2], truth.correction.sy[0],
                         truth.correction.sy[1], truth.correction.sy[2], truth.correction.sxy[0], truth.correction.sxy[1],
                         truth.correction.sxy[2], truth.damping_ratio, truth.frequency_scale,
                         truth.laser_on_delay_s, truth.laser_off_delay_s};
  ASSERT_EQ(id.values.size(), std::size(want));
  for (std::size_t k = 0; k < id.values.size(); ++k) {
    const auto& v = id.values[k];
    if (!v.determined) continue;  // held ones are reported; the rest must agree with the truth
    EXPECT_LT(std::abs(v.after - want[k]), 3.0 * v.sigma + 1e-9) << v.name << " = " << v.after << " ± " << v.sigma
                                                                  << ", truth " << want[k];
  }
  // The deflection per unit acceleration at the stations within ±3 %, the damping within ±30 %.
  for (const auto& s : id.scales) {
    const Mat2 C = m.model->compliance(s.point_m), S = truth.correction.matrix(s.point_m);
    const Mat2 Q = S * C * S;
    const Vec2 t(Q(0, 0) / C(0, 0), Q(1, 1) / C(1, 1));
    EXPECT_NEAR(s.scale.x(), t.x(), 0.03 * t.x());
    EXPECT_NEAR(s.scale.y(), t.y(), 0.03 * t.y());
  }
  EXPECT_NEAR(id.after.damping_ratio, truth.damping_ratio, 0.3 * truth.damping_ratio);
}

TEST(Identify, AJointFileOfAnotherJobIsRefusedNamingTheMark) {
  const Marked& m = marked();
  std::vector<ObservedMark> marks{{m.plate.strokes.front().id, {Vec2(0.2, 0.0), Vec2(0.2001, 0.0), Vec2(0.2002, 0.0), Vec2(0.2003, 0.0)}}};
  std::vector<compensation::JointCommand> other(m.commands.begin(), m.commands.begin() + 100);
  EXPECT_THROW((void)identify(other, m.robot, *m.model, m.plate, marks), Error);
  marks.front().id = "no-such-mark";
  EXPECT_THROW((void)identify(m.commands, m.robot, *m.model, m.plate, marks), Error);
}

}  // namespace
}  // namespace stiffpath::calibration
