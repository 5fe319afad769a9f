// ISO 9283 and VDI/DGQ 3441 statistics: thesis table 3.2, hand-computed cases, and bad trial files.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/repeatability.hpp"

namespace stiffpath::measurement {
namespace {

const PoseStatistics& find(const RepeatabilityReport& r, const std::string& mech, const std::string& point) {
  for (const auto& p : r.points) {
    if (p.mechanism == mech && p.point == point) return p;
  }
  throw std::runtime_error("no statistics for " + mech + " " + point);
}

TEST(Repeatability, ThesisTable32) {
  const auto report = analyse_repeatability(load_trials(thesis_repeatability()));
  ASSERT_EQ(report.points.size(), 9U);  // OC only: table 3.3 (SC) is missing
  ASSERT_EQ(report.missing.size(), 9U);
  EXPECT_NE(report.missing[0].find("SC x1y1: 0 complete trial(s) of 3"), std::string::npos) << report.missing[0];
  EXPECT_TRUE(report.vdi3441.empty());  // unidirectional data
  // x1y1, errors (0.794, 0.312), (0.791, 0.31), (0.792, 0.31) mm; values computed by hand (python).
  const auto& p = find(report, "OC", "x1y1");
  EXPECT_EQ(p.trials, 3);
  EXPECT_NEAR(p.mean_x_m * 1e3, 0.7923333, 1e-6);
  EXPECT_NEAR(p.ap_m * 1e3, 0.8510616, 1e-6);
  EXPECT_NEAR(p.l_mean_m * 1e3, 0.0014568, 1e-7);
  EXPECT_NEAR(p.s_l_m * 1e3, 0.0006951, 1e-7);
  EXPECT_NEAR(p.rp_m * 1e3, 0.0035422, 1e-7);
  const auto& q = find(report, "OC", "x3y5");
  EXPECT_NEAR(q.ap_m * 1e3, 0.0677020, 1e-6);
  EXPECT_NEAR(q.rp_m * 1e3, 0.0075416, 1e-7);
  // The "Max Diff." row of table 3.2, and the thesis's conclusion that all are below the CMM's 23 µm.
  EXPECT_NEAR(p.max_diff_x_m * 1e3, 0.003, 1e-9);
  EXPECT_NEAR(p.max_diff_y_m * 1e3, 0.002, 1e-9);
  EXPECT_NEAR(find(report, "OC", "x2y5").max_diff_y_m * 1e3, 0.008, 1e-9);
  for (const auto& s : report.points) {
    EXPECT_LT(std::max(s.max_diff_x_m, s.max_diff_y_m), 23e-6) << s.point;
    EXPECT_LT(s.rp_m, 23e-6) << s.point;
    EXPECT_GE(s.rp_m, s.l_mean_m);
  }
}

// Property: RP_l does not depend on where the cluster is, AP_p does; both scale with the data.
TEST(Repeatability, TranslationAndScalingProperties) {
  auto make = [](double dx, double scale) {
    std::vector<PositioningTrial> v;
    const double ex[] = {0.010, 0.013, 0.008, 0.011}, ey[] = {-0.002, 0.001, 0.000, -0.004};
    for (int j = 0; j < 4; ++j) {
      PositioningTrial t;
      t.point = "P";
      t.trial = j + 1;
      t.err_x_m = scale * (ex[j] + dx) * 1e-3;
      t.err_y_m = scale * ey[j] * 1e-3;
      v.push_back(t);
    }
    return analyse_repeatability(v).points.at(0);
  };
  const auto a = make(0.0, 1.0), b = make(0.5, 1.0), c = make(0.0, 3.0);
  EXPECT_NEAR(a.rp_m, b.rp_m, 1e-15);
  EXPECT_NEAR(b.mean_x_m - a.mean_x_m, 0.5e-3, 1e-15);
  EXPECT_NEAR(c.rp_m, 3.0 * a.rp_m, 1e-15);
  EXPECT_NEAR(c.ap_m, 3.0 * a.ap_m, 1e-15);
  EXPECT_NEAR(a.max_diff_x_m, 0.005e-3, 1e-15);
}

// VDI/DGQ 3441, one axis, two points, two approaches from each side (numbers worked out by hand):
// P1 up {10, 12} down {2, 4} µm → x̄ 7, U 8, s 1.41421 → Ps 8.48528; P2 up {−1, 1} down {−5, −3} → x̄ −2, U 4.
// Pa = 9; P = (7 + 4 + 4.24264) − (−2 − 2 − 4.24264) = 23.48528 µm.
TEST(Repeatability, Vdi3441HandComputed) {
  std::vector<PositioningTrial> v;
  auto add = [&](const char* point, int approach, int trial, double ex_um) {
    PositioningTrial t;
    t.mechanism = "OC";
    t.point = point;
    t.approach = approach;
    t.trial = trial;
    t.err_x_m = ex_um * 1e-6;
    t.err_y_m = 0.0;
    v.push_back(t);
  };
  add("P1", 1, 1, 10), add("P1", 1, 2, 12), add("P1", -1, 1, 2), add("P1", -1, 2, 4);
  add("P2", 1, 1, -1), add("P2", 1, 2, 1), add("P2", -1, 1, -5), add("P2", -1, 2, -3);
  const auto report = analyse_repeatability(v);
  ASSERT_EQ(report.vdi3441.size(), 2U);
  const auto& x = report.vdi3441[0];
  EXPECT_EQ(x.axis, 'x');
  ASSERT_EQ(x.points.size(), 2U);
  EXPECT_NEAR(x.points[0].mean_m, 7e-6, 1e-15);
  EXPECT_NEAR(x.points[0].reversal_span_m, 8e-6, 1e-15);
  EXPECT_NEAR(x.points[0].scatter_m, 6.0 * std::sqrt(2.0) * 1e-6, 1e-15);
  EXPECT_NEAR(x.position_deviation_m, 9e-6, 1e-15);
  EXPECT_NEAR(x.reversal_span_max_m, 8e-6, 1e-15);
  EXPECT_NEAR(x.reversal_span_mean_m, 6e-6, 1e-15);
  EXPECT_NEAR(x.uncertainty_m, 23.485281e-6, 1e-12);
  const auto& y = report.vdi3441[1];
  EXPECT_NEAR(y.uncertainty_m, 0.0, 1e-15);
  // ISO pools both approaches: P1 errors {10, 12, 2, 4} µm → AP = 7 µm.
  EXPECT_NEAR(report.points[0].ap_m, 7e-6, 1e-15);
}

std::string error_of(const std::string& text) {
  test::TempDir dir;
  const auto path = (dir / "t.csv").string();
  test::write_text(path, text);
  try {
    load_trials(path);
  } catch (const Error& e) {
    const std::string what = e.what();
    return what.substr(what.find("t.csv"));
  }
  return "no error";
}

TEST(RepeatabilityErrors, BadFilesNameLineAndColumn) {
  const std::string h = "point,x_mm,y_mm,trial,err_x_mm,err_y_mm\n";
  EXPECT_EQ(error_of(h + "P,1,2,1,0.1,0.2\nP,1,2,2,0.1,0.3\n"), "no error");
  EXPECT_NE(error_of("point,x_mm,y_mm,trial,err_x_mm\nP,1,2,1,0.1\n").find("t.csv:1:1: missing column 'err_y_mm'"),
            std::string::npos);
  EXPECT_NE(error_of("# comment first\npoint,x_mm,y_mm,trial,err_y_mm\n").find("t.csv:2:1: missing column 'err_x_mm'"),
            std::string::npos);
  EXPECT_NE(error_of("point,x_mm,y_mm,trial,err_x_um,err_y_mm\nP,1,2,1,0.1,0.2\n")
                .find("t.csv:1:23: column 'err_x_um': unit 'um' is not supported, use err_x_mm"),
            std::string::npos);
  EXPECT_NE(error_of(h + "P,1,2,1,nan,0.2\n").find("t.csv:2:9: column 'err_x_mm': 'nan' is not a finite number"),
            std::string::npos);
  EXPECT_NE(error_of(h + "P,1,2,1,0.1,0.2\nP,1,2,1,0.1,0.2\n").find("t.csv:3:7: column 'trial': duplicated trial 1"),
            std::string::npos);
  EXPECT_NE(error_of("point,x_mm,y_mm,trial,approach,err_x_mm,err_y_mm\nP,1,2,1,up,0.1,0.2\n")
                .find("column 'approach': 'up' is not an approach direction"),
            std::string::npos);
  EXPECT_NE(error_of(h + "P,1,2,0,0.1,0.2\n").find("column 'trial': trial numbers start at 1"), std::string::npos);
}

}  // namespace
}  // namespace stiffpath::measurement
