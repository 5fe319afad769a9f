// The marked path over the commanded one, its deviation magnified, and the deviation along the mark.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

//! A mark and the path it was meant to follow, in the robot's frame (m).
struct MarkPlotInput {
  std::vector<Eigen::Vector2d> commanded_m;  //!< the commanded laser path, in order (a polyline)
  std::vector<Eigen::Vector2d> mark_m;       //!< the mark, in order
  std::string source;                        //!< "simulated" or "measured": said in the title
  std::string label;                         //!< e.g. the joint file's name
};

//! What plot_mark drew.
struct MarkPlotSummary {
  double max_deviation_um = 0.0;   //!< largest distance of a mark point from the commanded polyline
  double rms_deviation_um = 0.0;
  double magnification = 1.0;      //!< deviations are drawn this many times larger
  double scale_bar_um = 0.0;       //!< the scale bar's length in deviation
};

//! Draws <name> (SVG, PNG, .gp, data <name>.tsv): on top the commanded path and the mark with each
//! point moved away from its nearest commanded point by `magnification` times its deviation (a 1-2-5
//! value chosen so that the largest deviation shows as about 4 % of the path's extent, or given), with a scale
//! bar for the deviation in µm; below, the signed deviation (µm, left of the direction of travel positive)
//! along the mark's arc length (mm). Polylines longer than 5000 points are thinned for the distance
//! search and the plot. Throws stiffpath::Error when either polyline has fewer than two points.
MarkPlotSummary plot_mark(const std::filesystem::path& dir, const std::string& name, const MarkPlotInput& input,
                          Style style = Style::screen, double magnification = 0.0);

}  // namespace stiffpath::report
