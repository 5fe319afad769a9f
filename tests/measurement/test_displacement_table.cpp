// Tests of the displacement-table format a user writes: the minimal columns, the optional ones' defaults, and located errors.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/data_check.hpp"
#include "stiffpath/measurement/displacement_table.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"

namespace stiffpath::measurement {
namespace {

DisplacementTable load_text(const std::string& text) {
  test::TempDir dir;
  test::write_text(dir / "t.csv", text);
  return load_displacement_table((dir / "t.csv").string());
}

std::string error_of(const std::string& text) {
  test::TempDir dir;
  test::write_text(dir / "t.csv", text);
  try {
    (void)load_displacement_table((dir / "t.csv").string());
  } catch (const Error& e) {
    return std::string(e.what()).substr((dir / "t.csv").string().size());
  }
  return "";
}

TEST(DisplacementTableFormat, TheMinimalColumnsAreEnoughInAnyOrder) {
  const auto t = load_text(
      "# my robot, loads in N\n"
      "dy_mm,dx_mm,F_N,direction,y_mm,x_mm,point\n"
      "0.002,0.010,50,+x,200,-20,a\n"
      "0.004,0.020,100,+x,200,-20,a\n"
      "-0.030,0.001,50,-y,200,-20,a\n"
      "0.003,0.011,50,+x,210,20,b\n");
  ASSERT_EQ(t.rows.size(), 4U);
  const auto& r = t.rows[1];
  EXPECT_EQ(r.mechanism, "");
  EXPECT_EQ(r.point, "a");
  EXPECT_EQ(r.direction, ForceDirection::plus_x);
  EXPECT_DOUBLE_EQ(r.x_m, -0.020);
  EXPECT_DOUBLE_EQ(r.force_N, 100.0);
  EXPECT_DOUBLE_EQ(r.nominal_force_N, 100.0);                          // F_nominal_N defaults to F_N
  EXPECT_DOUBLE_EQ(r.force_kgf, 100.0 / units::standard_gravity_m_s2);  // the reference step's load taken as zero
  EXPECT_EQ(r.step, 2);                                                // numbered per (point, direction)
  EXPECT_EQ(t.rows[2].step, 1);
  EXPECT_EQ(t.rows[3].step, 1);
  EXPECT_DOUBLE_EQ(*r.dx_m, 20e-6);
  EXPECT_FALSE(r.dz_m.has_value());
  EXPECT_FALSE(r.rx_rad.has_value());
  EXPECT_EQ(r.line, 4);
  EXPECT_EQ(t.sha256.size(), 64U);
  EXPECT_EQ(t.filter("").rows.size(), 4U);  // no mechanism: every row
}

TEST(DisplacementTableFormat, MissingColumnsAndBadCellsAreLocated) {
  EXPECT_EQ(error_of("point,x_mm,y_mm,direction,dx_mm,dy_mm\na,1,2,+x,0.1,0.2\n"),
            ":1:1: missing column 'F_N' (header: point,x_mm,y_mm,direction,dx_mm,dy_mm; expected "
            "point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm)");
  EXPECT_EQ(error_of("# c\npoint,x_m,y_mm,direction,F_N,dx_mm,dy_mm\na,1,2,+x,5,0.1,0.2\n"),
            ":2:7: column 'x_m': unit 'm' is not supported, use x_mm");
  EXPECT_EQ(error_of("point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm\na,1,2,+z,5,0.1,0.2\n"),
            ":2:7: column 'direction': '+z' is not a force direction (+x, -x, +y, -y)");
  EXPECT_EQ(error_of("point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm\na,1,2,+x,-5,0.1,0.2\n"),
            ":2:10: column 'F_N': force must be positive, got -5");
  EXPECT_EQ(error_of("point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm,step\na,1,2,+x,5,0.1,0.2,1\na,1,2,+x,9,0.1,0.2,1\n"),
            ":3: duplicated row: direction +x, point a, step 1 appears twice");
}

TEST(DisplacementTableFormat, AbsentQuantitiesAreZeroForVirtualCampaignsWhileGapsAreFitted) {
  const auto t = load_text(
      "point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm\n"
      "a,0,200,+x,50,0.010,0.002\n"
      "a,0,200,+x,100,0.020,\n");
  EXPECT_TRUE(has_gaps(t));  // dy missing in a row while others have it
  const auto filled = linear_truth(t);
  EXPECT_DOUBLE_EQ(*filled.rows[1].dz_m, 0.0);      // not in the table at all: zero
  EXPECT_NEAR(*filled.rows[1].dy_m, 4e-6, 1e-12);  // a gap: the series' line through the origin
  const auto full = load_text("point,x_mm,y_mm,direction,F_N,dx_mm,dy_mm\na,0,200,+x,50,0.010,0.002\n");
  EXPECT_FALSE(has_gaps(full));
  const auto zeroed = zero_absent_quantities(full);
  EXPECT_DOUBLE_EQ(*zeroed.rows[0].dx_m, 10e-6);  // measured cells unchanged
  EXPECT_DOUBLE_EQ(*zeroed.rows[0].ry_rad, 0.0);
}

TEST(DataCheckOptions, AnAsymmetricRobotSkipsTheSymmetryCheck) {
  const auto table = load_displacement_table(thesis_dataset()).filter("OC");
  DataCheckOptions options;
  options.ul_m = 0.160;  // the presets' replica
  EXPECT_FALSE(check_displacements(table, options).symmetry.empty());
  options.mirror_symmetric = false;
  const auto report = check_displacements(table, options);
  EXPECT_TRUE(report.symmetry.empty());
  // Not "could not run": it does not apply to this robot, and says so.
  EXPECT_NE(std::find(report.not_applicable.begin(), report.not_applicable.end(),
                      "symmetry: the robot is not its own mirror image about y = 0"),
            report.not_applicable.end());
  EXPECT_EQ(std::find(report.skipped.begin(), report.skipped.end(),
                      "symmetry: the robot is not its own mirror image about y = 0"),
            report.skipped.end());
  // One mechanism's rows: the OC vs SC comparison does not apply either.
  EXPECT_TRUE(report.comparison.empty());
  EXPECT_NE(std::find(report.not_applicable.begin(), report.not_applicable.end(),
                      "OC vs SC: the table holds the rows of one mechanism"),
            report.not_applicable.end());
}

}  // namespace
}  // namespace stiffpath::measurement
