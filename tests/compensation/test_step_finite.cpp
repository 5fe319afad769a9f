// Never NaN: every field of a step's result is finite for any finite input, whatever the options.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"

namespace stiffpath::compensation {
namespace {

bool finite(const Vec2& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

bool all_finite(const JointCommand& c) {
  return std::isfinite(c.t_s) && finite(c.q_rad) && finite(c.qd_rad_s) && finite(c.qdd_rad_s2) && finite(c.target_m) &&
         finite(c.command_m) && finite(c.force_N) && finite(c.deflection_m) && finite(c.load_torque_Nm);
}

// A finite number of any magnitude from 1e-300 to 1e300, either sign, sometimes 0.
double wild(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> exponent(-300.0, 300.0), unit(-1.0, 1.0);
  if (rng() % 8 == 0) return 0.0;
  return unit(rng) * std::pow(10.0, exponent(rng));
}

// A plausible planned sample in the workspace (5 g and beyond).
TaskSample plausible(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> x(0.16, 0.29), y(-0.09, 0.09), r(-1.0, 1.0);
  TaskSample s;
  s.position_m = {x(rng), y(rng)};
  s.velocity_m_s = {2 * r(rng), 2 * r(rng)};
  s.acceleration_m_s2 = {100 * r(rng), 100 * r(rng)};
  s.jerk_m_s3 = {2e4 * r(rng), 2e4 * r(rng)};
  s.snap_m_s4 = {1e7 * r(rng), 1e7 * r(rng)};
  return s;
}

TEST(StepFinite, EveryFieldIsFiniteForAnyFiniteInputAndOptions) {
  const auto robot = kinematics::load_robot("oc-gu");
  std::mt19937_64 rng(13);
  int refused_not_finite = 0, ok = 0;
  for (const char* name : {"thesis-oc", "thesis-oc-physical"}) {
    for (const auto policy : {compliance::OutsidePolicy::clamp, compliance::OutsidePolicy::extrapolate,
                              compliance::OutsidePolicy::error}) {
      auto loaded = compliance::load_model(name);
      loaded.model->set_outside_policy(policy);
      const std::shared_ptr<const compliance::Model> model(loaded.model.release());
      for (const Method method : {Method::quasi_static, Method::dynamic}) {
        for (const double gain : {0.0, 1.0, 1e300}) {
          for (const double zeta : {0.0, 0.05, 2.0}) {
            for (const bool check : {false, true}) {
              const Compensator comp(robot, model, {gain, true, check, method, zeta});
              for (int i = 0; i < 300; ++i) {
                TaskSample s = plausible(rng);
                // Replace some fields by wild values (huge, tiny, zero).
                if (i % 2) s.position_m = {wild(rng), wild(rng)};
                if (i % 3 == 0) s.velocity_m_s = {wild(rng), wild(rng)};
                if (i % 5 == 0) s.acceleration_m_s2 = {wild(rng), wild(rng)};
                if (i % 7 == 0) s.jerk_m_s3 = {wild(rng), wild(rng)};
                if (i % 11 == 0) s.snap_m_s4 = {wild(rng), wild(rng)};
                if (i % 13 == 0) s.t_s = wild(rng);
                const JointCommand c = comp.step(s);
                ASSERT_TRUE(all_finite(c)) << name << " method " << core::enum_name(method) << " gain " << gain << " i " << i;
                refused_not_finite += c.status == Status::not_finite;
                ok += c.status == Status::ok;
              }
            }
          }
        }
      }
    }
  }
  // The sweep reaches both outcomes: overflow refused as not_finite, and plausible samples commanded.
  EXPECT_GT(refused_not_finite, 0);
  EXPECT_GT(ok, 0);
}

TEST(StepFinite, NonFiniteInputIsRefusedWithFiniteFields) {
  const auto robot = kinematics::load_robot("oc-gu");
  auto loaded = compliance::load_model("thesis-oc");
  const Compensator comp(robot, std::shared_ptr<const compliance::Model>(loaded.model.release()),
                         {1.0, true, true, Method::dynamic, 0.05});
  TaskSample s;
  s.position_m = {0.222, 0.0};
  s.t_s = NAN;
  JointCommand c = comp.step(s);
  EXPECT_EQ(c.status, Status::not_finite);
  EXPECT_TRUE(all_finite(c));
  s.t_s = 0.0;
  s.jerk_m_s3 = {INFINITY, 0.0};
  c = comp.step(s);
  EXPECT_EQ(c.status, Status::not_finite);
  EXPECT_TRUE(all_finite(c));
}

}  // namespace
}  // namespace stiffpath::compensation
