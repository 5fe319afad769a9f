// The picture of a compliance campaign plan: where the robot can be measured, the points, and what the plan promises.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "stiffpath/calibration/campaign_plan.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

//! Three panels: the robot's usable region (grey lattice), the plan's rectangle and points; the physical model's
//! σ of a deflection under the largest load over the rectangle (µm); the residual spline's interpolation variance
//! relative to a regular grid's. Writes <dir>/<name>.tsv, <name>_map.tsv, .svg, .png, .gp.
void plot_campaign_plan(const std::filesystem::path& dir, const std::string& name, const calibration::CampaignPlan& plan,
                        const std::vector<kinematics::Vec2>& usable, const std::vector<calibration::CampaignMapPoint>& map,
                        const std::string& title, Style style = Style::screen);

}  // namespace stiffpath::report
