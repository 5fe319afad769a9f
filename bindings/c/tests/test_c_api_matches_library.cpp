// The C step, forward and inverse return bit for bit what the C++ library returns for the same input.
#include <gtest/gtest.h>

#include <ostream>
#include <random>
#include <string>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/stiffpath.h"

namespace {

using namespace stiffpath;

struct Case {
  const char* robot;
  const char* model;
  double gain;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.robot << " with " << c.model << " at gain " << c.gain; }

class CApi : public ::testing::TestWithParam<Case> {};

TEST_P(CApi, StepEqualsTheLibrarysStepFieldByField) {
  const Case c = GetParam();
  stiffpath_options options = stiffpath_default_options();
  options.gain = c.gain;
  char error[256];
  stiffpath_compensator* capi = stiffpath_compensator_create(c.robot, c.model, &options, error, sizeof error);
  ASSERT_NE(capi, nullptr) << error;

  const auto spec = kinematics::load_robot(c.robot);
  const std::shared_ptr<const compliance::Model> model(compliance::load_model(c.model).model.release());
  compensation::CompensatorOptions library_options;
  library_options.gain = c.gain;
  const compensation::Compensator library(spec, model, library_options);

  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> x(0.160, 0.296), y(-0.09, 0.09), v(-4.0, 4.0), a(-40, 40), j(-4e4, 4e4);
  int refused = 0;
  for (int i = 0; i < 5000; ++i) {
    compensation::TaskSample s;
    s.t_s = 5e-4 * i;
    s.position_m = {x(rng), y(rng)};
    s.velocity_m_s = {v(rng), v(rng)};
    s.acceleration_m_s2 = {a(rng), a(rng)};
    s.jerk_m_s3 = {j(rng), j(rng)};
    s.snap_m_s4 = {j(rng) * 100, j(rng) * 100};
    const stiffpath_task_sample cs = {s.t_s,
                                      {s.position_m.x(), s.position_m.y()},
                                      {s.velocity_m_s.x(), s.velocity_m_s.y()},
                                      {s.acceleration_m_s2.x(), s.acceleration_m_s2.y()},
                                      {s.jerk_m_s3.x(), s.jerk_m_s3.y()},
                                      {s.snap_m_s4.x(), s.snap_m_s4.y()}};
    stiffpath_joint_command out;
    const int status = stiffpath_compensator_step(capi, &cs, &out);
    const compensation::JointCommand expected = library.step(s);
    ASSERT_EQ(status, static_cast<int>(expected.status));
    ASSERT_EQ(out.status, status);
    refused += status != STIFFPATH_OK;
    EXPECT_EQ(out.t_s, expected.t_s);
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(out.q_rad[k], expected.q_rad[k]);
      EXPECT_EQ(out.qd_rad_s[k], expected.qd_rad_s[k]);
      EXPECT_EQ(out.qdd_rad_s2[k], expected.qdd_rad_s2[k]);
      EXPECT_EQ(out.target_m[k], expected.target_m[k]);
      EXPECT_EQ(out.command_m[k], expected.command_m[k]);
      EXPECT_EQ(out.force_N[k], expected.force_N[k]);
      EXPECT_EQ(out.deflection_m[k], expected.deflection_m[k]);
      EXPECT_EQ(out.load_torque_Nm[k], expected.load_torque_Nm[k]);
    }
    EXPECT_EQ(out.joint, expected.joint);
    EXPECT_EQ(out.outside_grid != 0, expected.outside_grid);
  }
  // The ranges are chosen so that both accepted and refused samples occur.
  EXPECT_GT(refused, 100);
  EXPECT_LT(refused, 4900);
  stiffpath_compensator_free(capi);
}

INSTANTIATE_TEST_SUITE_P(Robots, CApi,
                         ::testing::Values(Case{"oc-gu", "thesis-oc", 1.0}, Case{"sc-gl", "thesis-sc", 0.7},
                                           Case{"oc-gl", "thesis-oc-physical", 1.0}),
                         [](const ::testing::TestParamInfo<Case>& p) { return "case" + std::to_string(p.index); });

// The malformed-input corpus's robot and model files through the C interface: NULL and the located message
// (a model whose compliance is negated would reverse the correction; a deeply nested file once crashed the caller).
TEST(CApiRefusals, BadRobotAndModelFilesReturnNullWithTheirMessage) {
  const std::string bad = std::string(STIFFPATH_TEST_DATA_DIR) + "/bad/";
  char error[1024];
  for (const char* file : {"robot/nested_20000_objects.json", "robot/cg_height_1e6_mm.json",
                           "robot/moving_mass_5e-324_kg.json", "robot/table_and_model.json"}) {
    const std::string path = bad + file;
    EXPECT_EQ(stiffpath_robot_load(path.c_str(), error, sizeof error), nullptr) << file;
    EXPECT_NE(std::string(error).find(path + ":"), std::string::npos) << error;
  }
  for (const char* file : {"model/compliance_negated.json", "model/nested_20000_arrays.json"}) {
    const std::string path = bad + file;
    EXPECT_EQ(stiffpath_compensator_create("oc-gu", path.c_str(), nullptr, error, sizeof error), nullptr) << file;
    EXPECT_NE(std::string(error).find(path + ":"), std::string::npos) << error;
  }
  EXPECT_NE(std::string(error).find("LIMIT"), std::string::npos) << error;
}

TEST(CApiKinematics, ForwardAndInverseEqualTheLibrarys) {
  stiffpath_robot* robot = stiffpath_robot_load("sc-gu", nullptr, 0);
  ASSERT_NE(robot, nullptr);
  const auto five_bar = kinematics::load_robot("sc-gu").five_bar();
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> x(-0.31, 0.31), y(-0.31, 0.31);
  int unreachable = 0;
  for (int i = 0; i < 5000; ++i) {
    const double p[2] = {x(rng), y(rng)};
    double q[2] = {0, 0}, back[2] = {0, 0};
    const auto expected = five_bar.solve_inverse({p[0], p[1]});
    const int status = stiffpath_inverse(robot, p, q);
    ASSERT_EQ(status == STIFFPATH_OK, expected.status == kinematics::Reach::ok);
    if (status != STIFFPATH_OK) {
      ASSERT_EQ(status, STIFFPATH_UNREACHABLE);
      ++unreachable;
      continue;
    }
    EXPECT_EQ(q[0], expected.q.x());
    EXPECT_EQ(q[1], expected.q.y());
    ASSERT_EQ(stiffpath_forward(robot, q, back), STIFFPATH_OK);
    const auto p_back = five_bar.forward(expected.q);
    EXPECT_EQ(back[0], p_back.x());
    EXPECT_EQ(back[1], p_back.y());
  }
  EXPECT_GT(unreachable, 1000);
  stiffpath_robot_free(robot);
}

}  // namespace
