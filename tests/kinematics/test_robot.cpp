// Tests of mechanism presets and user files: values, round trip, and errors that name the bad field.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/mechanism_spec.hpp"
#include "stiffpath/kinematics/mobility.hpp"

namespace stiffpath::kinematics {
namespace {

TEST(MechanismSpec, PresetsCarryTheThesisValues) {
  for (const auto& name : preset_names()) {
    const MechanismSpec spec = load_mechanism(name);
    EXPECT_EQ(spec.name, name);
    EXPECT_DOUBLE_EQ(spec.link_length_m, 0.150);
    EXPECT_DOUBLE_EQ(spec.moving_mass_kg, 3.6);
    EXPECT_DOUBLE_EQ(spec.ug_m, 0.069);
    EXPECT_DOUBLE_EQ(spec.ul_m, 0.160);
    EXPECT_EQ(spec.build, name.substr(0, 2) == "oc" ? "OC" : "SC");
    EXPECT_DOUBLE_EQ(spec.cg_height_m, name.ends_with("gu") ? 0.0359 : 0.0053);
  }
}

TEST(MechanismSpec, WorkspaceJointRangeLiesWithinThePresetLimits) {
  const MechanismSpec spec = load_mechanism("oc-gu");
  const FiveBar robot = spec.five_bar();
  for (double x = 0.172132; x <= 0.272133; x += 0.005) {
    for (double y = -0.075; y <= 0.075001; y += 0.005) {
      int joint = -1;
      const Vec2 q = robot.inverse({x, y});
      EXPECT_EQ(check_joint_limits(spec, q, Vec2::Zero(), Vec2::Zero(), joint), JointCheck::ok);
    }
  }
}

TEST(MechanismSpec, JointLimitCheckNamesTheQuantity) {
  const MechanismSpec spec = load_mechanism("oc-gu");
  int joint = -1;
  EXPECT_EQ(check_joint_limits(spec, {2.5, -0.5}, Vec2::Zero(), Vec2::Zero(), joint), JointCheck::position);
  EXPECT_EQ(joint, 0);
  EXPECT_EQ(check_joint_limits(spec, {0.5, -0.5}, {0.0, 41.0}, Vec2::Zero(), joint), JointCheck::velocity);
  EXPECT_EQ(joint, 1);
  EXPECT_EQ(check_joint_limits(spec, {0.5, -0.5}, Vec2::Zero(), {5000.0, 0.0}, joint), JointCheck::acceleration);
  EXPECT_EQ(joint, 0);
  EXPECT_EQ(check_joint_limits(spec, {0.5, -0.5}, {std::nan(""), 0.0}, Vec2::Zero(), joint), JointCheck::velocity);
}

TEST(MechanismSpec, JsonRoundTrip) {
  const MechanismSpec spec = load_mechanism("sc-gl");
  const MechanismSpec back = parse_mechanism(to_json(spec), "roundtrip");
  EXPECT_EQ(back.name, spec.name);
  EXPECT_NEAR(back.cg_height_m, spec.cg_height_m, 1e-15);
  EXPECT_NEAR(back.joints[1].min_rad, spec.joints[1].min_rad, 1e-15);
  EXPECT_EQ(back.compliance_dataset, spec.compliance_dataset);
}

std::string error_of(const nlohmann::json& doc) {
  try {
    (void)parse_mechanism(doc, "user.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(MechanismSpec, BadFilesNameTheField) {
  const nlohmann::json good = to_json(load_mechanism("oc-gu"));
  auto missing = good;
  missing.erase("moving_mass_kg");
  EXPECT_EQ(error_of(missing), "user.json.moving_mass_kg: missing field");

  auto wrong_type = good;
  wrong_type["link_length_mm"] = "150";
  EXPECT_EQ(error_of(wrong_type), "user.json.link_length_mm: must be a number, got string \"150\"");

  auto negative = good;
  negative["link_length_mm"] = -150.0;
  EXPECT_EQ(error_of(negative), "user.json.link_length_mm: must be positive, got -150.0");

  auto joint = good;
  joint["joints"][1]["max_velocity_rad_s"] = 0;
  EXPECT_EQ(error_of(joint), "user.json.joints[1].max_velocity_rad_s: must be positive, got 0");

  auto build = good;
  build["build"] = "XX";
  EXPECT_NE(error_of(build).find("user.json.build: must be \"OC\" or \"SC\""), std::string::npos);

  auto cg = good;
  cg["cg"].erase("height_above_G_mm");
  EXPECT_EQ(error_of(cg), "user.json.cg.height_above_G_mm: missing field");
}

TEST(MechanismSpec, UserFileWithSyntaxErrorNamesLineAndColumn) {
  test::TempDir dir;
  test::write_text(dir / "bad.json", "{\n  \"name\": \"x\",\n  oops\n}\n");
  try {
    (void)load_mechanism((dir / "bad.json").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json:3:"), std::string::npos) << e.what();
  }
}

TEST(MechanismSpec, UnknownPresetListsTheKnownOnes) {
  try {
    (void)load_mechanism("oc-gx");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("oc-gu, oc-gl, sc-gu, sc-gl"), std::string::npos);
  }
}

TEST(Mobility, ThesisEquation32) {
  const auto linkages = thesis_linkages();
  ASSERT_EQ(linkages.size(), 3u);
  EXPECT_EQ(gruebler_kutzbach(linkages[0]), 3);
  EXPECT_EQ(gruebler_kutzbach(linkages[1]), 2);
  EXPECT_EQ(gruebler_kutzbach(linkages[2]), 1);
  EXPECT_EQ(actual_mobility(linkages[1]), 2);
  EXPECT_EQ(actual_mobility(linkages[2]), 2);
}

TEST(Mobility, HandCheckedLinkages) {
  // Four-bar: 3(4 − 4 − 1) + 4 = 1. Spatial 7R loop: 6(7 − 7 − 1) + 7 = 1.
  EXPECT_EQ(gruebler_kutzbach({"four-bar", 3, 4, {1, 1, 1, 1}, 0, ""}), 1);
  EXPECT_EQ(gruebler_kutzbach({"7R", 6, 7, std::vector<int>(7, 1), 0, ""}), 1);
  // Planar five-bar with a 2-DoF pin-in-slot joint: 3(5 − 5 − 1) + 6 = 3.
  EXPECT_EQ(gruebler_kutzbach({"five-bar slot", 3, 5, {1, 1, 1, 1, 2}, 0, ""}), 3);
  EXPECT_THROW((void)gruebler_kutzbach({"bad", 4, 4, {1}, 0, ""}), Error);
  EXPECT_THROW((void)gruebler_kutzbach({"bad", 3, 4, {3}, 0, ""}), Error);
}

}  // namespace
}  // namespace stiffpath::kinematics
