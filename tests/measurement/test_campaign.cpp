// Campaign files and their processing: eq. 2.3 on hand-computed readings, and every kind of bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <string>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/campaign.hpp"
#include "stiffpath/measurement/platform_pose.hpp"
#include "stiffpath/measurement/process_campaign.hpp"

namespace stiffpath::measurement {
namespace {

// The replica of the robots the hand campaign and the thesis were measured with (fig. 2.4).
ProcessOptions thesis_replica() {
  ProcessOptions o;
  o.mechanism = "OC";
  o.geometry = {0.069, 0.160};
  return o;
}

const std::string kHand = std::string(STIFFPATH_TEST_DATA_DIR) + "/campaign_hand.csv";

TEST(PlatformPose, Eq23PutsGOnTheSegmentAt69Over160) {
  const ReplicaGeometry geo{0.069, 0.160};  // the presets' replica: |UG| = 69 mm, |UL| = 160 mm
  const Vec3 U(0.1, 0.2, 0.3), L(0.1, 0.2, 0.14);
  const Vec3 G = cg_point(U, L, geo);
  EXPECT_NEAR((G - U).norm(), 0.069, 1e-15);
  EXPECT_NEAR((G - L).norm(), 0.091, 1e-15);
  // A tilted replica: G stays on UL at the same ratio.
  const Vec3 U2(0.01, -0.02, 0.16), L2(0.0, 0.0, 0.0);
  const Vec3 G2 = cg_point(U2, L2, geo);
  EXPECT_NEAR(((G2 - U2).cross(L2 - U2)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((G2 - U2).norm() / (L2 - U2).norm(), 69.0 / 160.0, 1e-14);
}

TEST(PlatformPose, TiltAndAxisAreInversesOverASeededSweep) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> angle(-0.3, 0.3), coord(-1.0, 1.0), length(0.05, 0.5);
  for (int i = 0; i < 1000; ++i) {
    const Tilt t{angle(rng), angle(rng)};
    const Vec3 L(coord(rng), coord(rng), coord(rng));
    const Vec3 U = L + length(rng) * axis_from_tilt(t);
    const Tilt back = tilt(U, L);
    ASSERT_NEAR(back.rx_rad, t.rx_rad, 1e-12);
    ASSERT_NEAR(back.ry_rad, t.ry_rad, 1e-12);
  }
  // Right-handed: rotating +z about +x by a small α moves it towards −y.
  const Vec3 a = axis_from_tilt({0.01, 0.0});
  EXPECT_LT(a.y(), 0.0);
  EXPECT_NEAR(a.y(), -std::sin(0.01), 1e-6);
}

TEST(ProcessCampaign, HandComputedCampaign) {
  const Campaign c = load_campaign(kHand);
  ASSERT_EQ(c.readings.size(), 4U);
  EXPECT_NEAR(c.readings[1].force_N, 5.0 * 9.80665, 1e-12);
  ProcessOptions options = thesis_replica();
  options.nominal_step_N = 50.0;  // the hand campaign has no force_nominal_N column: its steps are of 50 N
  const DisplacementTable t = process_campaign(c, options);
  ASSERT_EQ(t.rows.size(), 2U);
  const auto& s1 = t.rows[0];
  // Without a nominal step, the nominal force is the measured one (no other robot's loads are assumed).
  EXPECT_DOUBLE_EQ(process_campaign(c, thesis_replica()).rows[0].nominal_force_N, s1.force_N);
  EXPECT_EQ(s1.mechanism, "OC");
  EXPECT_EQ(s1.step, 1);
  EXPECT_NEAR(s1.force_N, (5.0 - 0.11) * 9.80665, 1e-9);  // relative to step 0 (table 2.1)
  EXPECT_DOUBLE_EQ(s1.nominal_force_N, 50.0);
  // U moved 0.16 mm along x, L stayed: G moves 0.16·(1 − 69/160) = 0.091 mm.
  EXPECT_NEAR(*s1.dx_m, 0.091e-3, 1e-12);
  EXPECT_NEAR(*s1.dy_m, 0.0, 1e-15);
  EXPECT_NEAR(*s1.dz_m, 0.0, 1e-12);
  EXPECT_NEAR(*s1.ry_rad, std::atan2(0.16, 160.0), 1e-12);
  EXPECT_NEAR(*s1.rx_rad, 0.0, 1e-15);
  EXPECT_FALSE(s1.spread.has_value());
  const auto& s2 = t.rows[1];
  EXPECT_NEAR(*s2.dx_m, 0.182e-3, 1e-12);
  EXPECT_NEAR(*s2.dy_m, 0.0, 1e-15);  // ±0.010 mm readings average out
  ASSERT_TRUE(s2.spread.has_value());
  EXPECT_EQ(s2.spread->readings, 2);
  // Readings of G_y: ±0.010·(1 − 69/160) mm; sample SD = √2 · 0.0056875 mm.
  EXPECT_NEAR(s2.spread->dy_m, std::sqrt(2.0) * 0.0056875e-3, 1e-12);
  EXPECT_NEAR(s2.spread->rx_rad, std::sqrt(2.0) * std::atan2(0.010, 160.0), 1e-12);
  EXPECT_NEAR(s2.spread->dx_m, 0.0, 1e-15);
}

TEST(ProcessCampaign, NominalForcesReplaceFNOnly) {
  const Campaign c = load_campaign(kHand);
  ProcessOptions o = thesis_replica();
  o.force_basis = ForceBasis::nominal;
  o.mechanism = "SC";
  // The campaign names no nominal loads: asking for them without a step is refused, not the thesis's 50 N.
  EXPECT_THROW((void)process_campaign(c, o), Error);
  o.nominal_step_N = 50.0;
  const DisplacementTable t = process_campaign(c, o);
  EXPECT_EQ(t.rows[1].mechanism, "SC");
  EXPECT_DOUBLE_EQ(t.rows[1].force_N, 100.0);
  EXPECT_DOUBLE_EQ(t.rows[1].force_kgf, 9.92);
  EXPECT_NEAR(*t.rows[1].dx_m, 0.182e-3, 1e-12);  // displacements do not depend on the force basis
}

TEST(ProcessCampaign, SavedTableKeepsTheSpreadAndReloads) {
  test::TempDir dir;
  const auto path = (dir / "table.csv").string();
  save_displacement_table(process_campaign(load_campaign(kHand), thesis_replica()), path);
  const DisplacementTable back = load_displacement_table(path);
  ASSERT_EQ(back.rows.size(), 2U);
  EXPECT_FALSE(back.rows[0].spread.has_value());
  ASSERT_TRUE(back.rows[1].spread.has_value());
  EXPECT_NEAR(back.rows[1].spread->dy_m, std::sqrt(2.0) * 0.0056875e-3, 1e-9);
  EXPECT_NEAR(*back.rows[0].dx_m, 0.091e-3, 1e-9);
}

// A table is never written that its own reader refuses: readings the campaign reader accepts (U 5.7e10 mm away,
// within its ±1e12) give a displacement beyond the table's ±100 mm; save names the readings' line and writes nothing.
TEST(ProcessCampaign, ATableItsOwnReaderWouldRefuseIsNotWritten) {
  test::TempDir dir;
  test::write_text(dir / "c.csv", "point,x_mm,y_mm,direction,step,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm\n"
                                  "P,200,0,+x,0,0.11,200,0,160,200,0,0\n"
                                  "P,200,0,+x,1,5,5.7e10,0,160,200,0,0\n"
                                  "P,200,0,+x,2,9.92,200.3,0,160,200,0,0\n");
  const auto table = process_campaign(load_campaign((dir / "c.csv").string()), thesis_replica());
  const auto path = (dir / "table.csv").string();
  try {
    save_displacement_table(table, path);
    FAIL();
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("c.csv:3: RANGE: dx of point P +x step 1 is"), std::string::npos) << what;
    EXPECT_NE(what.find("beyond the ±100 mm a displacement table holds; no table written"), std::string::npos) << what;
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  // The same readings within range are written and read back.
  test::write_text(dir / "ok.csv", "point,x_mm,y_mm,direction,step,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm\n"
                                   "P,200,0,+x,0,0.11,200,0,160,200,0,0\n"
                                   "P,200,0,+x,1,5,200.1,0,160,200,0,0\n"
                                   "P,200,0,+x,2,9.92,200.3,0,160,200,0,0\n");
  save_displacement_table(process_campaign(load_campaign((dir / "ok.csv").string()), thesis_replica()), path);
  EXPECT_EQ(load_displacement_table(path).rows.size(), 2U);
}

// ---- bad input: every error names file, line and column -----------------------------------------------

std::string error_of(const std::string& text) {
  test::TempDir dir;
  const auto path = (dir / "c.csv").string();
  test::write_text(path, text);
  try {
    load_campaign(path);
  } catch (const Error& e) {
    std::string what = e.what();
    const auto pos = what.find("c.csv");
    return pos == std::string::npos ? what : what.substr(pos);
  }
  return "no error";
}

const std::string kHeader = "point,x_mm,y_mm,direction,step,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm\n";
std::string row(int step, double kgf, const std::string& point = "P", const std::string& dir = "+x") {
  return point + ",200,0," + dir + "," + std::to_string(step) + "," + std::to_string(kgf) +
         ",200,0,160,200,0,0\n";
}
const std::string kGood = row(0, 0.11) + row(1, 5) + row(2, 9.92);

TEST(CampaignErrors, GoodBaselineLoads) { EXPECT_EQ(error_of(kHeader + kGood), "no error"); }

TEST(CampaignErrors, MissingColumn) {
  const std::string e = error_of("point,x_mm,y_mm,direction,step,force_kgf,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm\nP,1,2,+x,0,1,1,1,1,1,1\n");
  EXPECT_NE(e.find("c.csv:1:1: missing column 'Lz_mm'"), std::string::npos) << e;
}

TEST(CampaignErrors, WrongUnits) {
  std::string h = kHeader;
  h.replace(h.find("Uy_mm"), 5, "Uy_in");
  EXPECT_NE(error_of(h + kGood).find("c.csv:1:48: column 'Uy_in': unit 'in' is not supported, use Uy_mm"),
            std::string::npos)
      << error_of(h + kGood);
  std::string f = kHeader;
  f.replace(f.find("force_kgf"), 9, "force_lbf");
  EXPECT_NE(error_of(f + kGood).find("c.csv:1:32: column 'force_lbf': unit 'lbf'"), std::string::npos)
      << error_of(f + kGood);
  std::string both = kHeader;
  both.insert(both.find("Ux_mm"), "force_N,");
  EXPECT_NE(error_of(both).find("both force_kgf and force_N"), std::string::npos);
}

TEST(CampaignErrors, Step0Missing) {
  const std::string e = error_of(kHeader + row(1, 5) + row(2, 9.92) + row(3, 14.89));
  EXPECT_NE(e.find("c.csv:2: column 'step': point P, direction +x: step 0"), std::string::npos) << e;
}

TEST(CampaignErrors, FewerThanTwoLoadSteps) {
  const std::string e = error_of(kHeader + kGood + row(0, 0.11, "Q") + row(1, 5, "Q"));
  EXPECT_NE(e.find("c.csv:5: column 'step': point Q, direction +x: 1 loaded step(s)"), std::string::npos) << e;
}

TEST(CampaignErrors, NaNAndEmptyCells) {
  std::string bad = kGood;
  bad.replace(bad.rfind("160"), 3, "nan");
  const std::string e = error_of(kHeader + bad);
  EXPECT_NE(e.find("c.csv:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("column 'Uz_mm': 'nan' is not a finite number"), std::string::npos) << e;
  std::string empty = kGood;
  empty.replace(empty.find(",+x,1,") + 6, 8, "");
  EXPECT_NE(error_of(kHeader + empty).find("column 'force_kgf': value is missing"), std::string::npos);
}

TEST(CampaignErrors, DuplicatedRow) {
  const std::string e = error_of(kHeader + kGood + row(1, 5));
  EXPECT_NE(e.find("c.csv:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("duplicated reading: point P, direction +x, step 1, reading 1 already on line 3"),
            std::string::npos)
      << e;
}

TEST(CampaignErrors, OtherStructuralErrors) {
  EXPECT_NE(error_of(kHeader + kGood + row(3, 14.89, "P", "+z")).find("column 'direction': '+z' is not a force"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + row(-1, 0.11) + kGood).find("column 'step': -1 is out of range"), std::string::npos);
  std::string moved = kGood + "P,201,0,+x,3,14.89,200,0,160,200,0,0\n";
  EXPECT_NE(error_of(kHeader + moved).find("c.csv:5: column 'x_mm': point P is at (201.000"), std::string::npos);
  EXPECT_NE(error_of(kHeader + row(0, 0.11) + row(1, 0.05) + row(2, 9.92)).find("does not exceed step 0"),
            std::string::npos);
  EXPECT_NE(error_of(kHeader + "P,200,0,+x,0,0.11,1,1,1,1,1,1\n").find("U and L coincide"), std::string::npos);
}

}  // namespace
}  // namespace stiffpath::measurement
