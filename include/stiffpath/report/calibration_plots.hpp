// The calibration report's figure: every plate mark's misfit against the prediction, before and after the fit.
#pragma once

#include <filesystem>
#include <string>

#include "stiffpath/calibration/identify.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

//! Writes <dir>/<name>.tsv (per mark, one block: arc length along the mark in mm, the measured centre line's signed
//! distance from the predicted mark before and after the fit in µm) and, when gnuplot is installed, <name>.svg and
//! .png: the marks one after another along the x axis, before in grey and after in colour, each mark's id at its
//! start. Returns whether the figure was drawn (false: the data only, gnuplot missing). Throws stiffpath::Error when
//! `id` holds no mark.
bool plot_calibration_misfit(const std::filesystem::path& dir, const std::string& name,
                             const calibration::Identification& id, Style style = Style::screen);

}  // namespace stiffpath::report
