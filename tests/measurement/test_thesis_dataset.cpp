// The built-in thesis data set: shape, sample cells read off the seed by hand, and the seed's own statements.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::measurement {
namespace {

const DisplacementRow& find(const DisplacementTable& t, const std::string& mech, ForceDirection d,
                            const std::string& point, int step) {
  for (const auto& r : t.rows) {
    if (r.mechanism == mech && r.direction == d && r.point == point && r.step == step) return r;
  }
  throw std::runtime_error("row not found: " + mech + " " + point);
}

double total_mm(const DisplacementRow& r) {
  return 1e3 * std::sqrt(*r.dx_m * *r.dx_m + *r.dy_m * *r.dy_m + *r.dz_m * *r.dz_m);
}

void expect_mm(const std::optional<double>& v, double mm) {
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR(*v * 1e3, mm, 1e-12);
}
void expect_deg(const std::optional<double>& v, double deg) {
  ASSERT_TRUE(v.has_value());
  EXPECT_NEAR(units::rad_to_deg(*v), deg, 1e-12);
}

TEST(ThesisDataset, HasEveryMechanismDirectionPointAndStep) {
  const auto t = load_displacement_table(measurement::thesis_dataset());
  EXPECT_EQ(t.source, "builtin:thesis/displacements.csv");
  ASSERT_EQ(t.rows.size(), 300U);
  EXPECT_EQ(t.mechanisms(), (std::vector<std::string>{"OC", "SC"}));
  std::set<std::string> points;
  std::map<int, int> per_step;
  for (const auto& r : t.rows) {
    points.insert(r.point);
    ++per_step[r.step];
    EXPECT_TRUE(r.direction == ForceDirection::plus_x || r.direction == ForceDirection::minus_y);
    // Point id and coordinates agree with fig. 2.5.
    const int i = r.point[1] - '0', j = r.point[3] - '0';
    EXPECT_NEAR(r.x_m, 0.172132 + 0.050 * (i - 1), 1e-12) << r.point;
    EXPECT_NEAR(r.y_m, -0.075 + 0.0375 * (j - 1), 1e-12) << r.point;
    EXPECT_DOUBLE_EQ(r.nominal_force_N, 50.0 * r.step);
    EXPECT_NEAR(r.force_N, (r.force_kgf - 0.11) * 9.80665, 1e-4);
  }
  EXPECT_EQ(points.size(), 15U);
  for (int s = 1; s <= 5; ++s) EXPECT_EQ(per_step[s], 60) << "step " << s;
}

TEST(ThesisDataset, ForcesFollowTable21) {
  const auto t = load_displacement_table(measurement::thesis_dataset());
  const double kgf[] = {5.0, 9.92, 14.89, 19.83, 24.86};
  for (int s = 1; s <= 5; ++s) {
    const auto& r = find(t, "SC", ForceDirection::minus_y, "x2y3", s);
    EXPECT_DOUBLE_EQ(r.force_kgf, kgf[s - 1]);
  }
  EXPECT_NEAR(find(t, "OC", ForceDirection::plus_x, "x1y1", 5).force_N, 242.7146, 1e-4);
}

TEST(ThesisDataset, MissingCellsAreExactlyTheGarbledOnes) {
  const auto t = load_displacement_table(measurement::thesis_dataset());
  int missing_disp = 0, missing_angle = 0;
  for (const auto& r : t.rows) {
    missing_disp += !r.dx_m + !r.dy_m + !r.dz_m;
    missing_angle += !r.rx_rad + !r.ry_rad;
    // Only tables 2.2 (OC +x) and 3.8 (SC +x) are garbled.
    if (r.direction == ForceDirection::minus_y) {
      EXPECT_TRUE(r.dx_m && r.dy_m && r.dz_m) << r.point;
    }
  }
  EXPECT_EQ(missing_disp, 29);  // the 29 cells listed in data/thesis/README.md
  EXPECT_EQ(missing_angle, 0);
  const auto& a = find(t, "OC", ForceDirection::plus_x, "x1y1", 1);  // "0." | "061" | -0.031
  EXPECT_FALSE(a.dx_m);
  EXPECT_FALSE(a.dy_m);
  expect_mm(a.dz_m, -0.031);
  EXPECT_FALSE(find(t, "OC", ForceDirection::plus_x, "x2y1", 5).dx_m);  // "0.21"
  EXPECT_FALSE(find(t, "SC", ForceDirection::plus_x, "x3y2", 5).dz_m);  // "-0.1"
  EXPECT_FALSE(find(t, "SC", ForceDirection::plus_x, "x2y2", 4).dx_m);  // "181"
}

// Cells read off the seed by eye (table, row, column noted next to each).
TEST(ThesisDataset, SampleCellsMatchTheSeed) {
  const auto t = load_displacement_table(measurement::thesis_dataset());
  using D = ForceDirection;
  const auto& t22 = find(t, "OC", D::plus_x, "x1y2", 1);  // table 2.2, 50 N, x1y2
  expect_mm(t22.dx_m, 0.035);
  expect_mm(t22.dy_m, 0.027);
  expect_mm(t22.dz_m, -0.009);
  expect_mm(find(t, "OC", D::plus_x, "x3y4", 4).dy_m, -0.140);   // table 2.2, 200 N
  expect_mm(find(t, "OC", D::minus_y, "x2y4", 3).dz_m, 0.008);   // table 2.3, 150 N
  expect_mm(find(t, "OC", D::minus_y, "x3y1", 2).dy_m, -0.685);  // table 2.3, 100 N
  expect_mm(find(t, "SC", D::plus_x, "x2y5", 2).dz_m, -0.012);   // table 3.8, "$-0.012$"
  expect_mm(find(t, "SC", D::plus_x, "x1y4", 1).dz_m, 0.000);    // table 3.8, 50 N
  expect_mm(find(t, "SC", D::minus_y, "x2y2", 5).dy_m, -0.887);  // table 3.9, 250 N
  expect_mm(find(t, "SC", D::minus_y, "x1y2", 5).dy_m, -0.570);  // table 3.9, "$-0.570$"
  expect_deg(find(t, "OC", D::plus_x, "x3y5", 3).rx_rad, 0.023);   // table 3.4
  expect_deg(find(t, "OC", D::plus_x, "x1y1", 5).ry_rad, 0.077);   // table 3.4
  expect_deg(find(t, "OC", D::minus_y, "x2y1", 4).rx_rad, 0.037);  // table 3.5
  expect_deg(find(t, "OC", D::minus_y, "x1y3", 3).ry_rad, -0.010); // table 3.5
  expect_deg(find(t, "SC", D::plus_x, "x3y3", 1).rx_rad, -0.016);  // table 3.6
  expect_deg(find(t, "SC", D::plus_x, "x1y1", 5).ry_rad, 0.195);   // table 3.6
  expect_deg(find(t, "SC", D::minus_y, "x3y5", 5).ry_rad, -0.342); // table 3.7
  expect_deg(find(t, "SC", D::minus_y, "x2y2", 4).rx_rad, 0.009);  // table 3.7
}

// §3.3: "at x1y1 the total absolute compliant displacement for the over-constrained mechanism is
// 0.55 mm under the forces in x-direction ... at x3y5 [under −y] 1.73 mm to 3.33 mm".
TEST(ThesisDataset, TotalsQuotedInTheTextHold) {
  const auto t = load_displacement_table(measurement::thesis_dataset());
  EXPECT_NEAR(total_mm(find(t, "OC", ForceDirection::plus_x, "x1y1", 5)), 0.55, 0.005);
  EXPECT_NEAR(total_mm(find(t, "OC", ForceDirection::minus_y, "x3y5", 5)), 1.73, 0.005);
  EXPECT_NEAR(total_mm(find(t, "SC", ForceDirection::minus_y, "x3y5", 5)), 3.33, 0.005);
}

// The text's 1.53 mm for SC x1y1 (+x, 250 N) contradicts table 3.8: it is the sum of squares.
TEST(ThesisDataset, TheQuoted153mmIsTheSumOfSquaresNotTheNorm) {
  const auto t = load_displacement_table(measurement::thesis_dataset());
  const auto& r = find(t, "SC", ForceDirection::plus_x, "x1y1", 5);
  EXPECT_NEAR(total_mm(r), 1.236, 0.0005);
  EXPECT_GT(std::abs(total_mm(r) - 1.53), 0.25);
  EXPECT_NEAR(total_mm(r) * total_mm(r), 1.53, 0.005);
}

// §2.5: symmetric structure → no Δy on the x axis under +x (within the CMM's ±23 µm).
TEST(ThesisDataset, OcHasNoLateralDisplacementOnTheAxis) {
  const auto t = load_displacement_table(measurement::thesis_dataset()).filter("OC");
  int checked = 0;
  for (const auto& r : t.rows) {
    if (r.direction == ForceDirection::plus_x && r.point.ends_with("y3") && r.dy_m) {
      EXPECT_LT(std::abs(*r.dy_m), 23e-6) << r.point << " step " << r.step;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 14);  // 15 cells, one garbled
}

// Table 3.2: every "Max Diff." the seed prints equals max − min of the three trials it prints.
TEST(ThesisDataset, RepeatabilityMaxDiffRowsAgreeWithTheTrials) {
  const auto text = core::find_embedded("thesis/repeatability.csv");
  ASSERT_TRUE(text.has_value());
  std::istringstream in{std::string(*text)};
  core::CsvReader csv(in, "repeatability.csv");
  const auto c_mech = csv.column("mechanism"), c_point = csv.column("point");
  const auto c_ex = csv.column("err_x_mm"), c_ey = csv.column("err_y_mm");
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> oc;
  int sc_rows = 0;
  while (csv.next()) {
    if (csv.text(c_mech) == "SC") {
      EXPECT_FALSE(csv.optional_number(c_ex).has_value());
      ++sc_rows;
      continue;
    }
    auto& p = oc[std::string(csv.text(c_point))];
    p.first.push_back(csv.number(c_ex));
    p.second.push_back(csv.number(c_ey));
  }
  EXPECT_EQ(sc_rows, 27);
  ASSERT_EQ(oc.size(), 9U);
  const std::map<std::string, std::pair<double, double>> max_diff = {
      {"x1y1", {0.003, 0.002}}, {"x1y3", {0.003, 0.001}}, {"x1y5", {0.003, 0.002}},
      {"x2y1", {0.002, 0.003}}, {"x2y3", {0.003, 0.003}}, {"x2y5", {0.005, 0.008}},
      {"x3y1", {0.002, 0.003}}, {"x3y3", {0.002, 0.003}}, {"x3y5", {0.003, 0.008}}};
  auto range = [](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end()) - *std::min_element(v.begin(), v.end());
  };
  for (const auto& [point, d] : max_diff) {
    ASSERT_EQ(oc[point].first.size(), 3U) << point;
    EXPECT_NEAR(range(oc[point].first), d.first, 1e-9) << point;
    EXPECT_NEAR(range(oc[point].second), d.second, 1e-9) << point;
  }
}

}  // namespace
}  // namespace stiffpath::measurement
