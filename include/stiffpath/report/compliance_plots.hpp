// Compliance figures: the largest compliance over the workspace with principal directions, and
// measured vs predicted deflections of every model under cross-validation.
#pragma once

#include <filesystem>
#include <string>

#include "stiffpath/compliance/cross_validation.hpp"
#include "stiffpath/compliance/model.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

//! Heat map of the largest eigenvalue of C(p) (µm/N) over the model's grid rectangle (plus
//! `margin_m` around it), with the principal directions as arrows scaled by their eigenvalues.
//! Writes <dir>/<name>.tsv, <name>_axes.tsv, <name>.svg, <name>.png and <name>.gp. Returns the largest value.
double plot_compliance_map(const std::filesystem::path& dir, const std::string& name, const compliance::Model& model,
                           const std::string& title, double margin_m = 0.0, Style style = Style::screen);

//! Measured vs predicted Δx and Δy (µm) of every method's held-out predictions, one panel per
//! method, with the y = x line. Writes <dir>/<name>.tsv, .svg, .png, .gp.
void plot_cross_validation(const std::filesystem::path& dir, const std::string& name,
                           const compliance::CvReport& report, Style style = Style::screen);

}  // namespace stiffpath::report
