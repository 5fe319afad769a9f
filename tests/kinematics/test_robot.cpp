// Tests of robot presets and user robot files: values, round trip, joint ranges, and errors that name line and field.
#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/kinematics/robot_json.hpp"
#include "stiffpath/kinematics/mobility.hpp"

namespace stiffpath::kinematics {
namespace {

TEST(Robot, PresetsCarryTheThesisValues) {
  const auto names = preset_names();
  ASSERT_EQ(names, (std::vector<std::string>{"oc-gu", "oc-gl", "sc-gu", "sc-gl"}));
  for (const auto& name : names) {
    const Robot robot = load_robot(name);
    EXPECT_EQ(robot.name, name);
    EXPECT_TRUE(robot.preset);
    EXPECT_TRUE(robot.geometry.is_thesis_case());  // both actuators at the origin, four 150 mm links, [+1, -1]
    EXPECT_EQ(robot.geometry.proximal_m[0], 0.150);
    EXPECT_DOUBLE_EQ(robot.moving_mass_kg, 3.6);
    ASSERT_TRUE(robot.replica.has_value());
    EXPECT_DOUBLE_EQ(robot.replica->ug_m, 0.069);
    EXPECT_DOUBLE_EQ(robot.replica->ul_m, 0.160);
    EXPECT_EQ(robot.compliance.rows, name.substr(0, 2) == "oc" ? "OC" : "SC");
    EXPECT_EQ(robot.compliance.table, (core::DataRef{"thesis/displacements.csv", true}));
    EXPECT_FALSE(robot.compliance.method.has_value());  // the model cross-validation favours, as for any robot
    EXPECT_DOUBLE_EQ(robot.cg_height_m, name.ends_with("gu") ? 0.0359 : 0.0053);
    EXPECT_TRUE(robot.geometry.mirror_symmetric_about_x());
  }
}

TEST(Robot, WorkspaceJointRangeLiesWithinThePresetLimits) {
  const Robot spec = load_robot("oc-gu");
  const FiveBar robot = spec.five_bar();
  for (double x = 0.172132; x <= 0.272133; x += 0.005) {
    for (double y = -0.075; y <= 0.075001; y += 0.005) {
      int joint = -1;
      const Vec2 q = robot.inverse({x, y});
      EXPECT_EQ(check_joint_limits(spec.joints, q, Vec2::Zero(), Vec2::Zero(), joint), JointCheck::ok);
      EXPECT_EQ(spec.refusal({x, y}), "");
    }
  }
}

TEST(Robot, JointLimitCheckNamesTheQuantity) {
  const Robot spec = load_robot("oc-gu");
  int joint = -1;
  EXPECT_EQ(check_joint_limits(spec.joints, {2.5, -0.5}, Vec2::Zero(), Vec2::Zero(), joint), JointCheck::position);
  EXPECT_EQ(joint, 0);
  EXPECT_EQ(check_joint_limits(spec.joints, {0.5, -0.5}, {0.0, 41.0}, Vec2::Zero(), joint), JointCheck::velocity);
  EXPECT_EQ(joint, 1);
  EXPECT_EQ(check_joint_limits(spec.joints, {0.5, -0.5}, Vec2::Zero(), {5000.0, 0.0}, joint), JointCheck::acceleration);
  EXPECT_EQ(joint, 0);
  EXPECT_EQ(check_joint_limits(spec.joints, {0.5, -0.5}, {std::nan(""), 0.0}, Vec2::Zero(), joint),
            JointCheck::velocity);
}

TEST(Robot, InverseRefusesAPointWhoseAngleLeavesTheJointRange) {
  // (−100, 150) mm is inside the annulus and well conditioned, but eq. 2.2 puts θ1 at
  // atan2(150, −100) + acos(|p| / 300 mm) = 176.75°, beyond the preset's 135°.
  const Robot robot = load_robot("oc-gu");
  const Vec2 p{-0.100, 0.150};
  ASSERT_EQ(robot.five_bar().check_reach(p), Reach::ok);
  const double theta1 = std::atan2(0.150, -0.100) + std::acos(p.norm() / 0.300);
  EXPECT_NEAR(units::rad_to_deg(theta1), 176.75, 0.01);
  EXPECT_EQ(robot.refusal(p), fmt::format("joint theta1 would be at {:.3f} deg, outside its range [-45.0, 135.0] deg",
                                          units::rad_to_deg(theta1)));
  EXPECT_THROW((void)robot.inverse(p), Error);
  EXPECT_FALSE(robot.within_limits({theta1, 0.0}));
}

TEST(Robot, JsonRoundTripGivesTheSameRobot) {
  test::TempDir dir;
  const Robot robot = load_robot("sc-gl");
  nlohmann::json doc = to_json(robot);
  doc["compliance"]["table"] = "builtin:thesis/displacements.csv";
  test::write_text(dir / "copy.json", doc.dump(2));
  const Robot back = load_robot((dir / "copy.json").string());
  EXPECT_EQ(back.name, robot.name);
  EXPECT_TRUE(back.geometry == robot.geometry);
  EXPECT_EQ(back.geometry_hash(), robot.geometry_hash());
  EXPECT_NEAR(back.cg_height_m, robot.cg_height_m, 1e-15);
  EXPECT_NEAR(back.joints[1].min_rad, robot.joints[1].min_rad, 1e-15);
  EXPECT_EQ(back.compliance.table, robot.compliance.table);
  EXPECT_EQ(back.compliance.rows, "SC");
  EXPECT_FALSE(back.preset);
}

TEST(Robot, GeometryHashFollowsTheGeometryOnly) {
  const Robot a = load_robot("oc-gu");
  EXPECT_EQ(a.geometry_hash(), load_robot("sc-gl").geometry_hash());  // same five-bar, other data and CG
  EXPECT_EQ(a.geometry_hash().size(), 64U);
  for (int field = 0; field < 6; ++field) {
    Robot b = a;
    switch (field) {
      case 0: b.geometry.actuator_m[1].x() += 1e-6; break;
      case 1: b.geometry.proximal_m[0] += 1e-6; break;
      case 2: b.geometry.distal_m[1] += 1e-6; break;
      case 3: b.geometry.elbows[0] = -1; break;
      case 4: b.geometry.assembly = -1; break;
      default: b.moving_mass_kg = 2.0; break;
    }
    EXPECT_EQ(b.geometry_hash() == a.geometry_hash(), field == 5) << field;
  }
}

// The error of loading `doc` as user.json from a fresh folder (with data/t.csv beside it).
std::string error_of(const nlohmann::json& doc) {
  test::TempDir dir;
  std::filesystem::create_directories(dir / "data");
  test::write_text(dir / "data" / "t.csv", "point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm\np,200,0,+x,10,0.01,0\n");
  test::write_text(dir / "user.json", doc.dump(2));
  try {
    (void)load_robot((dir / "user.json").string());
  } catch (const Error& e) {
    const std::string what = e.what(), prefix = (dir / "user.json").string();
    EXPECT_EQ(what.rfind(prefix, 0), 0U) << what;
    return what.substr(prefix.size());
  }
  return "";
}

// A user's robot: the asymmetric example of the documentation.
nlohmann::json user_robot() {
  return nlohmann::json::parse(R"({
    "name": "mine",
    "left_actuator_mm": [-40, 0], "right_actuator_mm": [40, 0],
    "left_proximal_mm": 120, "right_proximal_mm": 130, "left_distal_mm": 180, "right_distal_mm": 170,
    "elbows": [1, -1],
    "moving_mass_kg": 2.2,
    "joints": [
      {"name": "theta1", "min_deg": 0, "max_deg": 200, "max_velocity_rad_s": 50, "max_acceleration_rad_s2": 8000},
      {"name": "theta2", "min_deg": -20, "max_deg": 180, "max_velocity_rad_s": 50, "max_acceleration_rad_s2": 8000}],
    "compliance": {"table": "data/t.csv"}
  })");
}

TEST(Robot, UserFileResolvesItsTableBesideItself) {
  EXPECT_EQ(error_of(user_robot()), "");
  test::TempDir dir;
  std::filesystem::create_directories(dir / "data");
  test::write_text(dir / "data" / "t.csv", "x");
  test::write_text(dir / "user.json", user_robot().dump());
  const Robot r = load_robot((dir / "user.json").string());
  EXPECT_EQ(r.compliance.table.path, (dir / "data" / "t.csv").lexically_normal().string());
  EXPECT_FALSE(r.compliance.table.builtin);
  EXPECT_FALSE(r.geometry.is_thesis_case());
  EXPECT_FALSE(r.geometry.mirror_symmetric_about_x());
  EXPECT_EQ(r.geometry.assembly, 1);  // the default
  EXPECT_FALSE(r.replica.has_value());
  EXPECT_EQ(r.cg_label, "G");
}

TEST(Robot, JointZeroOffsetsAreReadWrittenAndHashedOnlyWhenPresent) {
  test::TempDir dir;
  nlohmann::json doc = user_robot();
  doc.erase("compliance");
  test::write_text(dir / "plain.json", doc.dump());
  doc["joint_zero_offsets_deg"] = {0.05, -0.1};
  test::write_text(dir / "offset.json", doc.dump());
  const Robot plain = load_robot((dir / "plain.json").string()), offset = load_robot((dir / "offset.json").string());
  EXPECT_NEAR(offset.geometry.joint_zero_rad[0], 0.05 * std::numbers::pi / 180, 1e-18);
  EXPECT_NEAR(offset.geometry.joint_zero_rad[1], -0.1 * std::numbers::pi / 180, 1e-18);
  EXPECT_NE(offset.geometry_hash(), plain.geometry_hash());
  EXPECT_EQ(geometry_text(plain.geometry).find("joint_zero"), std::string::npos);  // old hashes unchanged
  EXPECT_FALSE(geometry_to_json(plain.geometry).contains("joint_zero_offsets_deg"));
  // Round trip through the file format: the same hash.
  test::write_text(dir / "back.json", to_json(offset).dump());
  EXPECT_EQ(load_robot((dir / "back.json").string()).geometry_hash(), offset.geometry_hash());
  // The commanded angle of a point is the offset-free one minus the offset.
  const Vec2 p(0.0, 0.21);
  EXPECT_NEAR(offset.inverse(p).x(), plain.inverse(p).x() - offset.geometry.joint_zero_rad[0], 1e-12);
  doc["joint_zero_offsets_deg"] = {0.0, 200.0};
  EXPECT_NE(error_of(doc).find("joint_zero_offsets_deg: each offset must lie within +-180 deg, got 200"), std::string::npos)
      << error_of(doc);
}

TEST(Robot, BadFilesNameTheLineAndTheField) {
  const nlohmann::json good = user_robot();
  auto missing = good;
  missing.erase("moving_mass_kg");
  EXPECT_EQ(error_of(missing), ": moving_mass_kg: missing field");  // no line: it is not there

  // dump(2) sorts the keys: "compliance" on line 2, "elbows" on line 5, "joints" on 6, "left_*" after.
  auto wrong_type = good;
  wrong_type["left_proximal_mm"] = "120";
  EXPECT_NE(error_of(wrong_type).find(": left_proximal_mm: must be a number, got string \"120\""), std::string::npos);

  auto negative = good;
  negative["right_distal_mm"] = -170.0;
  EXPECT_NE(error_of(negative).find(": right_distal_mm: must be positive, got -170.0"), std::string::npos);

  auto joint = good;
  joint["joints"][1]["max_velocity_rad_s"] = 0;
  EXPECT_NE(error_of(joint).find(": joints[1].max_velocity_rad_s: must be positive, got 0"), std::string::npos);

  auto unknown = good;
  unknown["compliance"]["dataset"] = "x.csv";
  EXPECT_EQ(error_of(unknown), ":3:5: compliance.dataset: unknown field (use table)");
  auto old = good;
  old["link_length_mm"] = 150;
  EXPECT_NE(error_of(old).find(": link_length_mm: unknown field (give left_proximal_mm"), std::string::npos);
  auto typo = good;
  typo["joints"][0]["max_deg_"] = 3;
  EXPECT_NE(error_of(typo).find(": joints[0].max_deg_: unknown field"), std::string::npos);

  auto elbows = good;
  elbows["elbows"] = {1, 0};
  EXPECT_NE(error_of(elbows).find(": elbows: must be [s_left, s_right] with each +1 or -1, got [1,0]"), std::string::npos);
  auto assembly = good;
  assembly["assembly"] = 2;
  EXPECT_NE(error_of(assembly).find(": assembly: must be +1 or -1, got 2"), std::string::npos);
  auto actuator = good;
  actuator["left_actuator_mm"] = {1, 2, 3};
  EXPECT_NE(error_of(actuator).find(": left_actuator_mm: must be an array of two numbers"), std::string::npos);

  auto no_table = good;
  no_table["compliance"]["table"] = "nowhere.csv";
  EXPECT_NE(error_of(no_table).find(": compliance.table: no such file: "), std::string::npos);

  auto home = good;
  home["home_mm"] = {0, 400};
  EXPECT_NE(error_of(home).find(": home_mm: is not reachable: too close to the stretched-out singularity"),
            std::string::npos);

  auto margin = good;
  margin["singularity_margin"] = {{"min_distance_mm", 130}};
  EXPECT_NE(error_of(margin).find(": singularity_margin.min_distance_mm: must be shorter than every link"),
            std::string::npos);
}

// Physical ranges where the values enter, and one key per meaning in the compliance section.
TEST(Robot, ValuesBeyondPhysicalRangesAndAmbiguousKeysAreRefused) {
  const nlohmann::json good = user_robot();
  const auto with = [&](const char* key, const nlohmann::json& value) {
    auto doc = good;
    doc[key] = value;
    return error_of(doc);
  };
  const std::string tiny = with("moving_mass_kg", 5e-324);
  EXPECT_NE(tiny.find("moving_mass_kg: RANGE: "), std::string::npos) << tiny;
  EXPECT_NE(tiny.find("e-324 kg is outside the physical range 0.001 to 1000 kg"), std::string::npos) << tiny;
  EXPECT_NE(with("moving_mass_kg", 2000.0).find("moving_mass_kg: RANGE"), std::string::npos);
  EXPECT_EQ(with("moving_mass_kg", 1000.0), "");  // the bounds are allowed
  EXPECT_NE(with("cg", {{"height_above_G_mm", 1e6}}).find("cg.height_above_G_mm: RANGE: 1000000.0 mm"), std::string::npos);
  EXPECT_EQ(with("cg", {{"height_above_G_mm", 1000}}), "");
  EXPECT_NE(with("left_proximal_mm", 0.5).find("left_proximal_mm: RANGE: 0.5 mm"), std::string::npos);
  EXPECT_NE(with("right_distal_mm", 2e4).find("right_distal_mm: RANGE"), std::string::npos);
  EXPECT_NE(with("left_actuator_mm", {2e4, 0}).find("left_actuator_mm: RANGE"), std::string::npos);
  auto fast = good;
  fast["joints"][0]["max_velocity_rad_s"] = 1e5;
  EXPECT_NE(error_of(fast).find("joints[0].max_velocity_rad_s: RANGE"), std::string::npos);

  // table and model: which compensates would be ambiguous (the model used to win silently)
  auto both = good;
  both["compliance"]["model"] = "data/t.csv";
  EXPECT_NE(error_of(both).find("compliance.model: give either a table"), std::string::npos);
  // rows and method describe a table; without one they mean nothing
  for (const char* key : {"rows", "method"}) {
    auto alone = good;
    alone["compliance"] = {{"model", "data/t.csv"}, {key, "OC"}};
    EXPECT_NE(error_of(alone).find(std::string("compliance.") + key + ": applies to a table"), std::string::npos) << key;
  }
}

TEST(Robot, ErrorPositionsPointAtTheKey) {
  test::TempDir dir;
  test::write_text(dir / "r.json", "{\n  \"name\": \"r\",\n  \"wheels\": 3\n}\n");
  try {
    (void)load_robot((dir / "r.json").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.where().column, 3);
    EXPECT_EQ(e.message(), "wheels: unknown field");
  }
}

TEST(Robot, UserFileWithSyntaxErrorNamesLineAndColumn) {
  test::TempDir dir;
  test::write_text(dir / "bad.json", "{\n  \"name\": \"x\",\n  oops\n}\n");
  try {
    (void)load_robot((dir / "bad.json").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json:3:"), std::string::npos) << e.what();
  }
}

TEST(Robot, UnknownPresetListsTheKnownOnes) {
  try {
    (void)load_robot("oc-gx");
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
