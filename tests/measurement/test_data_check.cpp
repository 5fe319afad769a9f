// Data checks: a synthetic table built to be linear, symmetric and reciprocal passes; planted faults are flagged
// exactly where planted; the thesis data set gives the figures its text states.
#include <gtest/gtest.h>

#include <cmath>

#include "stiffpath/measurement/data_check.hpp"

namespace stiffpath::measurement {
namespace {

TEST(LineFit, HandComputed) {
  const double x[] = {1, 2, 3}, y[] = {1, 2, 4};
  const LineFit f = fit_line(x, y);
  EXPECT_EQ(f.n, 3);
  EXPECT_NEAR(f.slope, 1.5, 1e-15);
  EXPECT_NEAR(f.intercept, -2.0 / 3.0, 1e-15);
  EXPECT_NEAR(f.r_squared, 1.0 - 9.0 / 252.0, 1e-15);
  EXPECT_NEAR(f.max_residual, 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(f.rms_residual, std::sqrt(1.0 / 18.0), 1e-15);
  EXPECT_NEAR(slope_through_origin(x, y), 17.0 / 14.0, 1e-15);
  EXPECT_EQ(fit_line(std::span<const double>(x, 1), std::span<const double>(y, 1)).slope, 0.0);
}

// Compliance field with the mirror symmetry y → −y and a symmetric 2×2 block (Maxwell–Betti):
// [dx dy] = C·F, C = [[a + b·x, c·y], [c·y, d]]; dz, rx (odd in y under Fx), ry (even) likewise.
DisplacementTable synthetic(const std::string& mechanism, double scale) {
  DisplacementTable t{"synthetic", {}, {}};
  const double kgf[] = {5.0, 9.92, 14.89, 19.83, 24.86};
  for (ForceDirection dir : {ForceDirection::plus_x, ForceDirection::minus_y}) {
    for (double x : {0.172132, 0.222132}) {
      for (int j = 0; j < 5; ++j) {
        const double y = -0.075 + 0.0375 * j;
        for (int s = 1; s <= 5; ++s) {
          DisplacementRow r;
          r.mechanism = mechanism;
          r.direction = dir;
          r.point = "x" + std::to_string(x > 0.2 ? 2 : 1) + "y" + std::to_string(j + 1);
          r.x_m = x;
          r.y_m = y;
          r.step = s;
          r.force_kgf = kgf[s - 1];
          r.force_N = (kgf[s - 1] - 0.11) * 9.80665;
          r.nominal_force_N = 50.0 * s;
          const double fx = direction_x(dir) * r.force_N, fy = direction_y(dir) * r.force_N;
          const double a = 1.5e-6 + 2e-6 * x, c = 1e-5 * y, d = 2.5e-6;
          r.dx_m = scale * (a * fx + c * fy);
          r.dy_m = scale * (c * fx + d * fy);
          r.dz_m = scale * (-3e-7 * fx + 4e-6 * y * fy);
          r.rx_rad = scale * (2e-5 * y * fx + 1e-6 * fy);
          r.ry_rad = scale * (5e-6 * fx + 3e-5 * y * fy);
          t.rows.push_back(r);
        }
      }
    }
  }
  return t;
}

// The presets' replica: |UL| sets an angle cell's accuracy, so the angles are checked too.
DataCheckOptions with_replica() {
  DataCheckOptions o;
  o.ul_m = 0.160;
  return o;
}

TEST(DataCheck, ConsistentSyntheticTablePassesEverything) {
  DisplacementTable t = synthetic("OC", 1.0);
  for (const auto& r : synthetic("SC", 2.0).rows) t.rows.push_back(r);
  const auto rep = check_displacements(t, with_replica());
  EXPECT_EQ(rep.linearity.size(), 2U * 2U * 10U * 5U);
  EXPECT_EQ(rep.reciprocity.size(), 20U);
  EXPECT_EQ(rep.comparison.size(), 2U * 10U * 5U);
  // Per mechanism, x, step: pairs (y1,y5), (y2,y4) × 5 quantities per direction, plus y3 against itself in
  // the quantities the mirror negates: dy, rx under +x; dx, dz, ry under −y (mirror of −y is −(−y)).
  EXPECT_EQ(rep.symmetry.size(), 2U * 2U * 5U * ((10U + 2U) + (10U + 3U)));
  EXPECT_EQ(rep.flagged_count(), 0);
  EXPECT_TRUE(rep.skipped.empty());
  for (const auto& l : rep.linearity) EXPECT_LT(l.fit.max_residual, 1e-15);
  for (const auto& r : rep.reciprocity) EXPECT_LT(r.difference_m, 1e-15);
  for (const auto& c : rep.comparison) EXPECT_NEAR(c.sc_total_m, 2.0 * c.oc_total_m, 1e-15);
}

TEST(DataCheck, PlantedFaultsAreFlaggedWhereTheyAre) {
  DisplacementTable t = synthetic("OC", 1.0);
  for (auto& r : t.rows) {
    if (r.point == "x1y1" && r.direction == ForceDirection::plus_x && r.step == 3) *r.dx_m += 60e-6;  // kink
  }
  const auto rep = check_displacements(t, with_replica());
  int lin = 0, sym = 0;
  for (const auto& l : rep.linearity) {
    if (l.flagged) {
      ++lin;
      EXPECT_EQ(l.point, "x1y1");
      EXPECT_EQ(l.quantity, Quantity::dx);
    }
  }
  for (const auto& s : rep.symmetry) {
    if (s.flagged) {
      ++sym;
      EXPECT_EQ(s.partner, "x1y5");
      EXPECT_EQ(s.step, 3);
      EXPECT_NEAR(s.expected - s.value, 60e-6, 1e-12);
    }
  }
  EXPECT_EQ(lin, 1);
  EXPECT_EQ(sym, 1);
  // The kink is below tolerance after spreading over the slope: reciprocity stays within 2 × 23 µm.
  for (const auto& r : rep.reciprocity) EXPECT_FALSE(r.flagged) << r.point;

  // A non-reciprocal point: dy under +x doubled at x2y2.
  DisplacementTable u = synthetic("OC", 1.0);
  for (auto& r : u.rows) {
    if (r.point == "x2y2" && r.direction == ForceDirection::plus_x) *r.dy_m *= 2.0;
  }
  for (const auto& r : check_displacements(u, with_replica()).reciprocity) EXPECT_EQ(r.flagged, r.point == "x2y2") << r.point;
}

// Nominal forces (50 … 250 N) are 2.9–4.3 % above the measured ones: regressed on them, an exactly linear
// series gets a slope smaller by the factor b of F_measured ≈ a + b·F_nominal.
TEST(DataCheck, NominalForcesScaleTheSlopes) {
  const DisplacementTable t = synthetic("OC", 1.0);
  DataCheckOptions nominal = with_replica();
  nominal.nominal_forces = true;
  const auto a = check_displacements(t, with_replica()), b = check_displacements(t, nominal);
  double fm[5], fn[5];
  for (int s = 0; s < 5; ++s) fm[s] = t.rows[static_cast<std::size_t>(s)].force_N, fn[s] = 50.0 * (s + 1);
  const double factor = fit_line(fn, fm).slope;
  // Table 2.1 by hand: kgf rises 49.63/10 = 4.963 kgf per step → 4.963 × 9.80665 / 50 = 0.973408.
  EXPECT_NEAR(factor, 0.973408, 1e-6);
  for (std::size_t i = 0; i < a.linearity.size(); ++i) {
    EXPECT_NEAR(b.linearity[i].fit.slope, factor * a.linearity[i].fit.slope, 1e-12 + 1e-9 * std::abs(a.linearity[i].fit.slope));
  }
}

TEST(DataCheck, ThesisDataSet) {
  DataCheckOptions options;
  options.ul_m = 0.160;  // the presets' replica: |UL| sets the angle cells' accuracy
  const auto rep = check_displacements(load_displacement_table(measurement::thesis_dataset()), options);
  // Table 3.4's odd cell (OC +x x3y5 rx = 0.023° at 150 N) breaks linearity beyond 2·23 µm/160 mm.
  bool found = false;
  for (const auto& l : rep.linearity) {
    if (l.mechanism == "OC" && l.direction == ForceDirection::plus_x && l.point == "x3y5" && l.quantity == Quantity::rx) {
      found = true;
      EXPECT_TRUE(l.flagged);
      EXPECT_EQ(l.fit.n, 5);
    }
  }
  EXPECT_TRUE(found);
  // §3.3's totals at 250 N, and the stiffer OC build everywhere beyond the accuracy.
  for (const auto& c : rep.comparison) {
    if (c.point == "x3y5" && c.direction == ForceDirection::minus_y && c.step == 5) {
      EXPECT_NEAR(c.oc_total_m * 1e3, 1.73, 0.005);
      EXPECT_NEAR(c.sc_total_m * 1e3, 3.33, 0.005);
    }
    if (c.point == "x1y1" && c.direction == ForceDirection::plus_x && c.step == 5) {
      EXPECT_NEAR(c.sc_total_m / c.oc_total_m, 1.236 / 0.549, 0.01);
    }
  }
  // §2.5: under +x, OC's y3 points show no Δy beyond the accuracy (self-symmetry dy = −dy).
  for (const auto& s : rep.symmetry) {
    if (s.mechanism == "OC" && s.point.ends_with("y3") && s.direction == ForceDirection::plus_x &&
        s.quantity == Quantity::dy) {
      EXPECT_FALSE(s.flagged) << s.point << " step " << s.step;
    }
  }
  // Missing cells are skipped and said so (OC +x 50 N cells garbled in the seed).
  EXPECT_FALSE(rep.skipped.empty() && rep.linearity.empty());
}

}  // namespace
}  // namespace stiffpath::measurement
