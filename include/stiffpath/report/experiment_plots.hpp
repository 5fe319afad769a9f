// Figures of the twin's experiment like thesis figs. 4.9–4.11: length and deviation area against acceleration.
#pragma once

#include <filesystem>
#include <vector>

#include "stiffpath/simulation/experiment.hpp"

namespace stiffpath::report {

//! Writes one data file per configuration (experiment_<mechanism>_<off|on>_<motion>.tsv: acceleration_g,
//! length_mm, deviation_area_mm2, max_deviation_mm) and renders, with gnuplot, fig_4_9a_y_length,
//! fig_4_9b_y_deviation, fig_4_10a_x_length, fig_4_10b_x_deviation and fig_4_11_triangle_deviation
//! (SVG + PNG; one line per mechanism, dashed without and solid with compensation, as in the thesis).
//! Returns the figure names. Throws stiffpath::Error when gnuplot fails.
std::vector<std::string> write_experiment_figures(const std::filesystem::path& dir,
                                                  const std::vector<simulation::RunResult>& results);

}  // namespace stiffpath::report
