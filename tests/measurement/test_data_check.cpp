// Data checks: a synthetic table built to be linear, symmetric and reciprocal passes; planted faults are flagged
// exactly where planted; the thesis data set gives the figures its text states.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "stiffpath/core/error.hpp"

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

// The mirror partner of each point is the first row, in the table's order, at (x, −y) within 1 µm: the binned
// search (n log n) finds the same partner as the plain scan over every row (the oracle here), on points placed
// on a jittered grid where some lie just inside and some just outside the tolerance, and some have no mirror.
TEST(DataCheck, MirrorPartnersAreTheFirstRowsWithinOneMicrometreAsAPlainScanFindsThem) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.9e-6, 0.9e-6);
  DisplacementTable t{"jittered", {}, {}};
  int k = 0;
  for (int i = 0; i < 12; ++i) {
    for (int j = -6; j <= 6; ++j) {
      if ((i * 7 + j * 3) % 11 == 0) continue;  // holes: some points lose their mirror
      DisplacementRow r;
      r.mechanism = (i % 5 == 0) ? "SC" : "OC";
      r.direction = ForceDirection::plus_x;
      r.point = "p" + std::to_string(k++);
      r.x_m = 0.2 + 0.001 * i + jitter(rng);
      r.y_m = 0.0005 * j + jitter(rng);
      r.step = 1;
      r.force_N = r.nominal_force_N = 50.0;
      r.dx_m = 1e-5;
      r.dy_m = 0.0;
      t.rows.push_back(r);
    }
  }
  std::vector<std::string> skipped;
  const auto results = check_symmetry(t, DataCheckOptions{}, skipped);
  std::map<std::pair<std::string, std::string>, std::string> expected;  // (mechanism, point) -> partner
  for (const auto& r : t.rows) {
    for (const auto& p : t.rows) {
      if (p.mechanism == r.mechanism && std::abs(p.x_m - r.x_m) < 1e-6 && std::abs(p.y_m + r.y_m) < 1e-6) {
        expected[{r.mechanism, r.point}] = p.point;
        break;
      }
    }
  }
  int compared = 0;
  for (const auto& s : results) {
    ASSERT_TRUE(expected.contains({s.mechanism, s.point})) << s.point;
    EXPECT_EQ(s.partner, (expected[{s.mechanism, s.point}])) << s.point;
    ++compared;
  }
  EXPECT_GT(compared, 20);
  std::size_t without = 0;
  for (const auto& r : t.rows) without += !expected.contains({r.mechanism, r.point});
  EXPECT_EQ(skipped.size(), without);  // each point without a mirror is said once
  EXPECT_GT(without, 5U);
}

// A series of one or two cells fits any line exactly (one cell: slope 0): it is not counted as checked.
TEST(DataCheck, SeriesOfFewerThanThreeCellsAreSkippedNotCountedAsChecked) {
  DisplacementTable t = synthetic("OC", 1.0);
  DataCheckOptions with_angles;
  with_angles.ul_m = 0.160;  // the replica's |UL|: rx and ry are checked too
  const std::size_t full = check_displacements(t, with_angles).linearity.size();
  // Keep only step 1 of one series (+x at x1y1).
  std::erase_if(t.rows, [](const DisplacementRow& r) {
    return r.point == "x1y1" && r.direction == ForceDirection::plus_x && r.step > 1;
  });
  const auto rep = check_displacements(t, with_angles);
  EXPECT_EQ(rep.linearity.size(), full - 5);  // its five quantities are not checked
  for (const auto& l : rep.linearity) EXPECT_GE(l.fit.n, 3) << l.point;
  int said = 0;
  for (const auto& s : rep.skipped) said += s.find("x1y1") != std::string::npos && s.find("only 1 cell") != std::string::npos;
  EXPECT_EQ(said, 5);
}

// A table of several mechanisms is never pooled: naming none is refused with the mechanisms it holds.
TEST(DataCheck, ATableOfSeveralMechanismsIsNeverPooled) {
  DisplacementTable t = synthetic("OC", 1.0);
  const DisplacementTable sc = synthetic("SC", 2.0);
  t.rows.insert(t.rows.end(), sc.rows.begin(), sc.rows.end());
  EXPECT_EQ(t.filter("SC").rows.size(), sc.rows.size());
  try {
    (void)t.filter("");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the table holds the rows of 2 mechanisms (OC, SC)"), std::string::npos);
  }
  EXPECT_EQ(synthetic("", 1.0).filter("").rows.size(), synthetic("", 1.0).rows.size());
}

}  // namespace
}  // namespace stiffpath::measurement
