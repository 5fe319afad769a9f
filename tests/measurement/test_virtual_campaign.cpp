// Round trips truth → virtual CMM readings → processing: exact without noise, within the noise's statistics with it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/process_campaign.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"

namespace stiffpath::measurement {
namespace {

// Processing with the presets' replica (fig. 2.4), as the campaigns were simulated.
ProcessOptions replica() {
  ProcessOptions o;
  o.mechanism = "OC";
  o.geometry = {0.069, 0.160};
  return o;
}

DisplacementTable oc_truth() { return linear_truth(load_displacement_table(measurement::thesis_dataset()).filter("OC")); }

struct Stats {
  double mean = 0.0, sd = 0.0;
  std::size_t n = 0;
};
Stats stats(const std::vector<double>& v) {
  Stats s;
  s.n = v.size();
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(s.n);
  for (double x : v) s.sd += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(s.sd / static_cast<double>(s.n - 1));
  return s;
}

TEST(LinearTruth, IsCompleteAndProportionalToForce) {
  const auto t = oc_truth();
  ASSERT_EQ(t.rows.size(), 150U);
  for (const auto& r : t.rows) {
    ASSERT_TRUE(r.dx_m && r.dy_m && r.dz_m && r.rx_rad && r.ry_rad);
  }
  // Same series, steps 1 and 5: the ratio of any quantity is the ratio of the forces.
  const auto& s1 = t.rows[0];
  const auto& s5 = t.rows[4];
  ASSERT_EQ(s1.point, s5.point);
  EXPECT_NEAR(*s5.dy_m / *s1.dy_m, s5.force_N / s1.force_N, 1e-12);
  // OC x1y1 +x: dx slope fitted to the four legible cells (0.198 … 0.479 mm at 96 … 243 N).
  const double f[] = {96.2032365, 144.9423, 193.3871, 242.7146};
  const double d[] = {0.198e-3, 0.289e-3, 0.389e-3, 0.479e-3};
  double sfd = 0, sff = 0;
  for (int i = 0; i < 4; ++i) sfd += f[i] * d[i], sff += f[i] * f[i];
  EXPECT_NEAR(*s5.dx_m, s5.force_N * sfd / sff, 1e-9);
}

TEST(VirtualCampaign, NoiseFreeRoundTripIsExact) {
  const auto truth = oc_truth();
  VirtualCampaignOptions o;
  o.geometry = {0.069, 0.160};  // the presets' replica
  o.step0_kgf = step0_load_kgf(truth);  // the truth's own reference load
  o.noise_sigma_m = 0.0;
  o.g_height_m = 0.25;
  o.initial_tilt = {0.02, -0.015};  // a platform that is not level at step 0
  o.readings_per_step = 2;
  const Campaign c = simulate_campaign(truth, o);
  EXPECT_EQ(c.readings.size(), 30U * 6U * 2U);  // 30 series × (step 0 + 5 steps) × 2 readings
  const DisplacementTable back = process_campaign(c, replica());
  ASSERT_EQ(back.rows.size(), truth.rows.size());
  for (std::size_t i = 0; i < back.rows.size(); ++i) {
    const auto& a = back.rows[i];
    const auto& b = truth.rows[i];
    ASSERT_EQ(a.point, b.point);
    ASSERT_EQ(a.step, b.step);
    EXPECT_NEAR(a.force_N, b.force_N, 1e-4);  // the CSV keeps F_N to 4 decimals
    EXPECT_NEAR(*a.dx_m, *b.dx_m, 1e-12);
    EXPECT_NEAR(*a.dy_m, *b.dy_m, 1e-12);
    EXPECT_NEAR(*a.dz_m, *b.dz_m, 1e-12);
    EXPECT_NEAR(*a.rx_rad, *b.rx_rad, 1e-11);
    EXPECT_NEAR(*a.ry_rad, *b.ry_rad, 1e-11);
    ASSERT_TRUE(a.spread.has_value());
    EXPECT_LT(a.spread->dx_m, 1e-12);
  }
}

// With the arm's noise, the recovered displacement errors divided by their predicted σ must look like
// N(0, 1): σ_G = σ·√((1 − r)² + r²) (eq. 2.3, r = 69/160), σ_d = σ_G·√(1/n_k + 1/n_0).
TEST(VirtualCampaign, NoisyRoundTripMatchesTheNoiseStatistics) {
  const auto thesis = load_displacement_table(measurement::thesis_dataset());
  for (int readings : {1, 4}) {
    const double r = 69.0 / 160.0, n = readings;
    const double sigma = VirtualCampaignOptions{}.noise_sigma_m;
    const double sigma_g = sigma * std::sqrt((1 - r) * (1 - r) + r * r);
    const double sigma_d = sigma_g * std::sqrt(2.0 / n);
    const double sigma_angle = sigma * std::sqrt(2.0) / 0.160 * std::sqrt(2.0 / n);
    std::vector<double> zd, za, spread_var;
    // Pooled over both mechanisms and four seeds (the step-0 error is shared by a series' five steps).
    for (const char* mech : {"OC", "SC"}) {
      const auto truth = linear_truth(thesis.filter(mech));
      for (unsigned seed = 1; seed <= 4; ++seed) {
        VirtualCampaignOptions o;
        o.geometry = {0.069, 0.160};
        o.step0_kgf = step0_load_kgf(truth);
        o.readings_per_step = readings;
        o.seed = 100 * seed + static_cast<unsigned>(readings);
        const DisplacementTable back = process_campaign(simulate_campaign(truth, o), replica());
        for (std::size_t i = 0; i < back.rows.size(); ++i) {
          const auto& a = back.rows[i];
          const auto& b = truth.rows[i];
          zd.push_back((*a.dx_m - *b.dx_m) / sigma_d);
          zd.push_back((*a.dy_m - *b.dy_m) / sigma_d);
          zd.push_back((*a.dz_m - *b.dz_m) / sigma_d);
          za.push_back((*a.rx_rad - *b.rx_rad) / sigma_angle);
          za.push_back((*a.ry_rad - *b.ry_rad) / sigma_angle);
          if (a.spread) spread_var.push_back(a.spread->dx_m * a.spread->dx_m / (sigma_g * sigma_g));
        }
      }
    }
    const Stats sd = stats(zd), sa = stats(za);
    ASSERT_EQ(sd.n, 3600U);
    EXPECT_NEAR(sd.mean, 0.0, 0.08) << readings;
    EXPECT_NEAR(sd.sd, 1.0, 0.06) << readings;
    EXPECT_NEAR(sa.mean, 0.0, 0.08) << readings;
    EXPECT_NEAR(sa.sd, 1.0, 0.06) << readings;
    if (readings > 1) {  // the mean sample variance of the readings is unbiased for σ_G²
      ASSERT_EQ(spread_var.size(), 1200U);
      EXPECT_NEAR(stats(spread_var).mean, 1.0, 0.08);
    }
  }
}

TEST(VirtualCampaign, SameSeedSameReadingsAndFileRoundTrip) {
  const auto truth = oc_truth();
  VirtualCampaignOptions o;
  o.geometry = {0.069, 0.160};  // the presets' replica
  o.step0_kgf = step0_load_kgf(truth);  // the truth's own reference load
  o.seed = 7;
  const Campaign a = simulate_campaign(truth, o), b = simulate_campaign(truth, o);
  ASSERT_EQ(a.readings.size(), b.readings.size());
  EXPECT_EQ(a.readings[17].U, b.readings[17].U);
  o.seed = 8;
  EXPECT_NE(simulate_campaign(truth, o).readings[17].U, a.readings[17].U);

  test::TempDir dir;
  const auto path = (dir / "campaign.csv").string();
  save_campaign(a, path);
  const Campaign back = load_campaign(path);
  ASSERT_EQ(back.readings.size(), a.readings.size());
  for (std::size_t i = 0; i < a.readings.size(); i += 37) {
    EXPECT_LT((back.readings[i].U - a.readings[i].U).norm(), 1e-9);  // 6 decimals of mm
    EXPECT_NEAR(back.readings[i].force_N, a.readings[i].force_N, 1e-5);
  }
}

TEST(VirtualCampaign, RejectsIncompleteTruthAndBadOptions) {
  const auto thesis = load_displacement_table(measurement::thesis_dataset()).filter("OC");
  try {
    simulate_campaign(thesis, VirtualCampaignOptions{.geometry = {0.069, 0.160}});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("builtin:thesis/displacements.csv:3: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("column 'dx_mm'"), std::string::npos) << e.what();
  }
  VirtualCampaignOptions o;
  o.geometry = {0.069, 0.160};  // the presets' replica
  o.readings_per_step = 0;
  EXPECT_THROW(simulate_campaign(oc_truth(), o), Error);
  o.readings_per_step = 1;
  EXPECT_THROW(simulate_campaign(linear_truth(load_displacement_table(measurement::thesis_dataset())), o), Error);  // two mechanisms
}

}  // namespace
}  // namespace stiffpath::measurement
