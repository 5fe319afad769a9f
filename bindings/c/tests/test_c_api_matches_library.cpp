// The C step, forward and inverse return bit for bit what the C++ library returns for the same input.
#include <gtest/gtest.h>

#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/job/joint_record.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/prepared_job.hpp"
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

// Where each field of the joint record (job::kJointFields) lives in stiffpath_joint_command: its member of the same
// name. A member added to the table without a case here is a -Wswitch warning and a failure below.
bool c_value(const stiffpath_joint_command& c, const job::JointField& f, double& v) {
  const int k = f.component;
  switch (f.member) {
    case job::JointMember::t_s: v = c.t_s; return true;
    case job::JointMember::q_rad: v = c.q_rad[k]; return true;
    case job::JointMember::qd_rad_s: v = c.qd_rad_s[k]; return true;
    case job::JointMember::qdd_rad_s2: v = c.qdd_rad_s2[k]; return true;
    case job::JointMember::laser: v = c.laser; return true;
    case job::JointMember::power: v = c.power; return true;
    case job::JointMember::target_m: v = c.target_m[k]; return true;
    case job::JointMember::command_m: v = c.command_m[k]; return true;
    case job::JointMember::force_N: v = c.force_N[k]; return true;
    case job::JointMember::line: v = c.line; return true;
  }
  return false;
}

class Keep final : public job::JointWriter {
 public:
  void write(const compensation::JointCommand& c) override { commands.push_back(c); }
  void finish() override {}
  std::vector<compensation::JointCommand> commands;
};

// The C interface's job hands over every field a joint file holds, with the library's job's values (the same
// JobSpec: the thesis's method on oc-gu): the C struct is checked against the field table, not a copy of it.
TEST(CApiJob, EveryJointFileFieldIsAMemberOfTheCommand) {
  const std::string gcode = std::string(STIFFPATH_TEST_DATA_DIR) + "/../../examples/triangle.gcode";
  stiffpath_job_options options = stiffpath_default_job_options();
  options.thesis = 1;
  std::vector<stiffpath_joint_command> from_c;
  const auto sink = [](const stiffpath_joint_command* c, void* user) {
    static_cast<std::vector<stiffpath_joint_command>*>(user)->push_back(*c);
    return 0;
  };
  char error[512];
  ASSERT_EQ(stiffpath_run_job("oc-gu", nullptr, gcode.c_str(), &options, sink, &from_c, error, sizeof error), STIFFPATH_OK)
      << error;
  const auto robot = kinematics::load_robot("oc-gu");
  job::JobSpec spec = job::thesis_job(robot);
  Keep library;
  job::run(job::prepare(std::move(spec), job::Program::file(gcode)), &library);
  ASSERT_EQ(from_c.size(), library.commands.size());
  ASSERT_GT(from_c.size(), 100U);
  int laser_on = 0;
  for (std::size_t i = 0; i < from_c.size(); ++i) {
    laser_on += from_c[i].laser;
    for (const auto& f : job::kJointFields) {
      double v = 0.0;
      ASSERT_TRUE(c_value(from_c[i], f, v)) << "stiffpath_joint_command has no member for " << f.csv_name;
      ASSERT_EQ(v, job::value_of(library.commands[i], f)) << f.csv_name << " of command " << i;
    }
  }
  EXPECT_GT(laser_on, 0);  // the laser and power fields were exercised
}

}  // namespace
