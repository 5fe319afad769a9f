// Geometry calibration figures: each reading's misfit before and after, and a pose plan over the robot's reach.
#pragma once

#include <filesystem>
#include <string>

#include "stiffpath/calibration/geometry_fit.hpp"
#include "stiffpath/calibration/geometry_plan.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

//! |measured − predicted| of every reading (µm, log scale) with the robot file's geometry (instrument frame
//! fitted alone) and with the calibrated one, beside the instrument's 2σ. Writes <dir>/<name>.tsv, .svg, .png, .gp.
void plot_geometry_residuals(const std::filesystem::path& dir, const std::string& name,
                             const calibration::GeometryFitResult& fit, const std::string& title,
                             Style style = Style::screen);

//! The robot's reachable region (the plan's candidate lattice), its actuators and the planned poses numbered in
//! measuring order. Writes <dir>/<name>.tsv, .svg, .png, .gp.
void plot_geometry_plan(const std::filesystem::path& dir, const std::string& name, const calibration::GeometryPlan& plan,
                        const kinematics::Robot& robot, const std::string& title, Style style = Style::screen);

}  // namespace stiffpath::report
