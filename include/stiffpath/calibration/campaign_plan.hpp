// Designing a compliance campaign: the points and load steps the physical model and its residual spline learn most from.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compliance/model.hpp"
#include "stiffpath/kinematics/robot.hpp"
#include "stiffpath/measurement/displacement_table.hpp"

namespace stiffpath::calibration {

//! Settings of plan_campaign(), with documented defaults.
struct CampaignPlanSettings {
  int points = 12;  //!< measurement points (4 … kMaxCampaignPoints), the region's four corners among them
  //! The region to model (robot frame, m); empty: the largest axis-aligned rectangle in which every point is
  //! reachable within the singularity margin, the joint limits and max_condition_number.
  std::optional<compliance::GridBounds> region;
  //! The loads available (N, relative to step 0), e.g. the robot's table's steps; load_steps of them are chosen.
  std::vector<double> candidate_loads_N;
  int load_steps = 3;  //!< loaded steps per series (≥ 2: eq. 4.8's line needs two; 3 lets `data check` test linearity)
  //! Load directions measured at every point (one series each); a direction along x and one along y give the
  //! per-point fits of eq. 4.8 that the residual spline interpolates.
  std::vector<measurement::ForceDirection> directions{measurement::ForceDirection::plus_x,
                                                      measurement::ForceDirection::plus_y};
  double step0_kgf = 0.0;  //!< the reference step's hanging load (the wire system's own weight), kgf
  //! σ of one measured displacement (m): the instrument's noise through eq. 2.3 and the step-0 difference.
  double cell_sigma_m = 11.6e-6;
  double max_condition_number = 4.0;  //!< the default region keeps to this (and the robot's margin)
  int candidate_lattice = 21;         //!< candidates on a lattice × lattice grid over the region
  int exchange_passes = 3;            //!< passes of point exchange after the greedy choice
  //! Instead of choosing points, lay them on the regular nx × ny grid of about `points` (for comparison).
  bool regular_grid = false;
};

//! The most points a campaign plan may have.
inline constexpr int kMaxCampaignPoints = 200;

//! A planned campaign and what it promises.
struct CampaignPlan {
  compliance::GridBounds region;
  std::vector<kinematics::Vec2> points;  //!< the four corners first, then in the order chosen
  std::vector<double> loads_N;           //!< the loaded steps, ascending
  std::vector<measurement::ForceDirection> directions;
  double step0_kgf = 0.0;
  //! The plan's criterion, each term relative to a regular grid of as many points over the region (1 = as good):
  //! the physical model's mean prediction variance over the region (its parameters' covariance from the cells'
  //! noise) and the residual spline's mean interpolation variance (how far the region is from measured points).
  double physical_ratio = 1.0;
  double interpolation_ratio = 1.0;
  //! The regular grid behind the ratios (nx × ny over the region).
  int grid_nx = 0, grid_ny = 0;
};

//! Chooses the points (greedy from the region's corners, then point exchange) that minimise the sum of the two
//! ratios above, and the load steps (of candidate_loads_N, the largest always) that maximise Σ(F − F̄)² with
//! step 0's F = 0: the slope of eq. 4.8 determined best. Deterministic. Throws stiffpath::Error when the region
//! holds no reachable rectangle, a corner of a given region is out of reach, or there are too few candidate loads.
CampaignPlan plan_campaign(const kinematics::Robot& robot, const CampaignPlanSettings& settings);

//! The largest axis-aligned rectangle inside the robot's usable region (reach, singularity margin, joint
//! limits, condition number ≤ max_condition_number), on a lattice of about `cells` points, checked along its
//! edges.
compliance::GridBounds largest_usable_rectangle(const kinematics::Robot& robot, double max_condition_number,
                                                int cells = 10000);

//! The criterion's two mean variances for any layout (`points` over `region`, with the plan's loads and
//! directions): the physical model's mean prediction variance of C's entries ((m/N)²) and the mean
//! interpolation variance (dimensionless).
std::pair<double, double> campaign_criterion(const kinematics::Robot& robot, const compliance::GridBounds& region,
                                             const std::vector<kinematics::Vec2>& points, const CampaignPlan& plan,
                                             double cell_sigma_m);

//! What a plan promises over its region, on an n × n lattice: the physical model's σ of a deflection under the
//! largest load along x and along y (m, the root mean of the two), from its parameters' covariance given the cells'
//! noise; and the interpolation variance relative to that of the regular grid (mean 1 over the grid's region).
struct CampaignMapPoint {
  kinematics::Vec2 p;
  double physical_sigma_m = 0.0;
  double interpolation_relative = 0.0;
};
std::vector<CampaignMapPoint> campaign_map(const kinematics::Robot& robot, const CampaignPlan& plan, double cell_sigma_m,
                                           int n = 41);
//! The usable region on a lattice of about `cells` points (reach, margin, joint limits, condition number), for
//! pictures.
std::vector<kinematics::Vec2> usable_lattice(const kinematics::Robot& robot, double max_condition_number, int cells = 6000);

//! The plan as rows of a displacement table without displacements: point, x_mm, y_mm, direction, step,
//! force_kgf, F_N (one row per point, direction and loaded step).
measurement::DisplacementTable plan_rows(const CampaignPlan& plan);
//! Writes plan_rows() as CSV (`point,x_mm,y_mm,direction,step,force_kgf,F_N`), atomically.
void save_campaign_plan(const CampaignPlan& plan, const std::string& path);
//! Reads a plan file (the columns above; errors name file, line and column) as displacement rows without
//! displacements.
measurement::DisplacementTable load_campaign_plan(const std::string& path);

//! The plan's rows with the displacements `field` predicts (dx, dy = C(p)·F; dz, rx, ry zero): a truth for
//! measurement::simulate_campaign().
measurement::DisplacementTable truth_from_field(const measurement::DisplacementTable& plan_rows,
                                                const compliance::Model& field);

}  // namespace stiffpath::calibration
