// Campaign design: the usable rectangle, the plan's points and loads, and a planned campaign against a grid on a known field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cli_runner.hpp"
#include "stiffpath/calibration/campaign_plan.hpp"
#include "stiffpath/compliance/physical_spline_model.hpp"
#include "stiffpath/compliance/point_fit.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/measurement/process_campaign.hpp"
#include "stiffpath/measurement/virtual_campaign.hpp"
#include "stiffpath/simulation/structural_terms.hpp"

namespace stiffpath::calibration {
namespace {

using kinematics::Vec2;

kinematics::Robot asym() { return kinematics::load_robot(STIFFPATH_SOURCE_DIR "/examples/robots/asym_5bar.json"); }

// A field of another family than the physical model's (a compliant frame that rotates about the actuators'
// midpoint), written in the robot's own terms.
constexpr const char* kField =
    "actuator_rad_per_Nm=4e-5/6e-5,proximal_bending_per_Nm2=2e-4,distal_axial_m_per_N=1e-7,base_x_m_per_N=2e-7,"
    "base_rotation_rad_per_Nm=2e-5";

CampaignPlanSettings settings(int points) {
  CampaignPlanSettings s;
  s.points = points;
  s.candidate_loads_N = {50, 100, 150, 200};
  s.directions = {measurement::ForceDirection::plus_x, measurement::ForceDirection::minus_y};
  s.region = compliance::GridBounds{-0.06, 0.06, 0.17, 0.25};  // the example table's rectangle
  s.candidate_lattice = 13;
  return s;
}

TEST(CampaignPlan, TheDefaultRegionIsUsableEverywhere) {
  const auto robot = asym();
  const compliance::GridBounds r = largest_usable_rectangle(robot, 4.0, 3000);
  const auto fb = robot.five_bar();
  std::printf("largest usable rectangle: x [%.1f, %.1f] mm, y [%.1f, %.1f] mm\n", r.x_min * 1e3, r.x_max * 1e3,
              r.y_min * 1e3, r.y_max * 1e3);
  EXPECT_GT((r.x_max - r.x_min) * (r.y_max - r.y_min), 0.01);  // at least 100 cm² for this 300 mm robot
  for (int i = 0; i <= 30; ++i) {
    for (int j = 0; j <= 30; ++j) {
      const Vec2 p(r.x_min + (r.x_max - r.x_min) * i / 30.0, r.y_min + (r.y_max - r.y_min) * j / 30.0);
      ASSERT_TRUE(robot.refusal(p).empty()) << p.transpose();
      ASSERT_LE(fb.condition_number(robot.inverse(p)), 4.0) << p.transpose();
    }
  }
}

TEST(CampaignPlan, PointsCoverTheRegionAndLoadsSpreadTheLine) {
  const auto robot = asym();
  const CampaignPlan plan = plan_campaign(robot, settings(12));
  ASSERT_EQ(plan.points.size(), 12u);
  const auto& r = plan.region;
  for (const Vec2& c : {Vec2(r.x_min, r.y_min), Vec2(r.x_max, r.y_min), Vec2(r.x_min, r.y_max), Vec2(r.x_max, r.y_max)}) {
    EXPECT_NE(std::find_if(plan.points.begin(), plan.points.end(), [&](const Vec2& p) { return (p - c).norm() < 1e-9; }),
              plan.points.end());
  }
  for (const auto& p : plan.points) {
    EXPECT_TRUE(r.grown(1e-9).contains(p));
    EXPECT_TRUE(robot.refusal(p).empty());
  }
  // {0} ∪ loads with the largest Σ(F − F̄)²: 50, 150, 200 N (SS 21 875 against 20 000 for 100, 150, 200).
  EXPECT_EQ(plan.loads_N, (std::vector<double>{50, 150, 200}));
  EXPECT_LT(plan.physical_ratio + plan.interpolation_ratio, 2.0);  // better than the grid by its own criterion
  EXPECT_EQ(plan.grid_nx * plan.grid_ny, 12);
  // The criterion recomputed from the points alone gives the same ratios.
  CampaignPlanSettings g = settings(12);
  g.regular_grid = true;
  const CampaignPlan grid = plan_campaign(robot, g);
  const auto [pp, pi] = campaign_criterion(robot, r, plan.points, plan, g.cell_sigma_m);
  const auto [gp, gi] = campaign_criterion(robot, r, grid.points, plan, g.cell_sigma_m);
  EXPECT_NEAR(pp / gp, plan.physical_ratio, 1e-9);
  EXPECT_NEAR(pi / gi, plan.interpolation_ratio, 1e-9);
}

// The target: for a new robot, a planned campaign of N points predicts a known field over the region better
// than a regular grid of the same N. Each campaign is simulated from CMM readings with the arm's noise (11.5 µm per coordinate),
// processed by eq. 2.3 and fitted with physical-spline; the error is |C_model − C_field|_F × 100 N over a 41 × 41
// lattice. Independent of the plan's own criterion: what the fitted model gets wrong.
TEST(CampaignPlan, APlannedCampaignRecoversAKnownFieldBetterThanAGridOfAsManyPoints) {
  const auto robot = asym();
  ASSERT_TRUE(robot.replica);
  double planned_sum = 0.0, grid_sum = 0.0;
  int planned_wins = 0;
  constexpr int kSeeds = 3;
  for (const int n : {9, 16}) {
    // A new robot: the plan's own region, the largest usable rectangle (300 × 128 mm here).
    CampaignPlanSettings s = settings(n);
    s.region.reset();
    const CampaignPlan plan = plan_campaign(robot, s);
    s.regular_grid = true;
    const CampaignPlan grid = plan_campaign(robot, s);
    const auto field = simulation::structural_model_from_terms(robot, kField, plan.region);
    for (int seed = 1; seed <= kSeeds; ++seed) {
      double rms[2];
      for (int which = 0; which < 2; ++which) {
        const CampaignPlan& layout = which == 0 ? plan : grid;
        measurement::VirtualCampaignOptions v;
        v.geometry = {robot.replica->ug_m, robot.replica->ul_m};
        v.seed = static_cast<std::uint64_t>(seed);
        v.step0_kgf = layout.step0_kgf;
        const auto campaign = measurement::simulate_campaign(truth_from_field(plan_rows(layout), *field), v);
        measurement::ProcessOptions po;
        po.mechanism = "";
        po.geometry = v.geometry;
        const auto table = measurement::process_campaign(campaign, po);
        const auto model = compliance::fit_physical_spline_model(
            compliance::group_by_point(table, compliance::ForceConvention::measured), robot.geometry, "virtual", false);
        model->set_outside_policy(compliance::OutsidePolicy::extrapolate);
        double sum = 0.0;
        const auto& r = plan.region;
        for (int i = 0; i <= 40; ++i) {
          for (int j = 0; j <= 40; ++j) {
            const Vec2 p(r.x_min + (r.x_max - r.x_min) * i / 40.0, r.y_min + (r.y_max - r.y_min) * j / 40.0);
            const double e = (model->compliance(p) - field->compliance(p)).norm() * 100.0;
            sum += e * e;
          }
        }
        rms[which] = std::sqrt(sum / (41 * 41));
      }
      std::printf("N = %d seed %d: field error RMS planned %.1f um, grid %.1f um\n", n, seed, rms[0] * 1e6, rms[1] * 1e6);
      planned_sum += rms[0];
      grid_sum += rms[1];
      planned_wins += rms[0] < rms[1] ? 1 : 0;
    }
  }
  EXPECT_LT(planned_sum, 0.95 * grid_sum);  // at least 5 % better on average
  EXPECT_GE(planned_wins, 2 * kSeeds - 1);   // and in (nearly) every campaign
}

TEST(CampaignPlan, APlanFileRoundTripsAndItsErrorsNameTheLine) {
  test::TempDir dir;
  CampaignPlanSettings s = settings(6);
  s.step0_kgf = 0.25;
  const CampaignPlan plan = plan_campaign(asym(), s);
  save_campaign_plan(plan, (dir / "plan.csv").string());
  const auto rows = load_campaign_plan((dir / "plan.csv").string());
  ASSERT_EQ(rows.rows.size(), 6u * 2u * 3u);
  for (const auto& r : rows.rows) {
    EXPECT_NEAR(r.force_kgf - r.force_N / 9.80665, 0.25, 1e-6);  // step 0 carries the robot's own 0.25 kgf
    EXPECT_FALSE(r.dx_m.has_value());
  }
  test::write_text(dir / "bad.csv", "point,x_mm,y_mm,direction,step,force_kgf,F_N\nc1,0,200,+x,1,5.1,50\nc1,0,200,+z,2,10.2,100\n");
  try {
    (void)load_campaign_plan((dir / "bad.csv").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_NE(std::string(e.what()).find("+z"), std::string::npos) << e.what();
  }
}

TEST(StructuralTerms, ActuatorsAloneGiveJKJtAndBadTermsAreNamed) {
  const auto robot = asym();
  const auto model = simulation::structural_model_from_terms(robot, "actuator_rad_per_Nm=2e-5/5e-5", {-0.06, 0.06, 0.17, 0.25});
  const auto fb = robot.five_bar();
  for (const Vec2& p : {Vec2(0.0, 0.2), Vec2(0.05, 0.24)}) {
    const auto J = fb.jacobian(fb.solve_inverse(p).q);
    const compliance::Mat2 want = J * Vec2(2e-5, 5e-5).asDiagonal() * J.transpose();
    EXPECT_LT((model->compliance(p) - want).norm(), 1e-3 * want.norm());
  }
  EXPECT_THROW((void)simulation::structural_model_from_terms(robot, "actuator=1e-5", {-0.06, 0.06, 0.17, 0.25}), Error);
  EXPECT_THROW((void)simulation::structural_model_from_terms(robot, "base_x_m_per_N=1e-7/2e-7", {-0.06, 0.06, 0.17, 0.25}), Error);
  EXPECT_THROW((void)simulation::structural_model_from_terms(robot, "distal_axial_m_per_N=-1", {-0.06, 0.06, 0.17, 0.25}), Error);
}

}  // namespace
}  // namespace stiffpath::calibration
