// Figures of a results table in the layout of thesis figs. 4.9–4.11: length and deviation area against acceleration.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "stiffpath/report/gnuplot.hpp"
#include "stiffpath/report/results_table.hpp"

namespace stiffpath::report {

//! Renders, with gnuplot, fig_4_9a_y_length, fig_4_9b_y_deviation, fig_4_10a_x_length,
//! fig_4_10b_x_deviation and fig_4_11_triangle_deviation (those whose motion the table holds) into
//! `dir`: for each, <name>.tsv (one block per robot × compensation: acceleration_g, length_mm,
//! deviation_area_mm2), .svg, .png and the script .gp. One line per robot, dashed without and solid
//! with compensation, as in the thesis; titles say whether the marks were simulated or measured.
//! Returns the figure names. Throws stiffpath::Error when gnuplot fails.
std::vector<std::string> write_results_figures(const std::filesystem::path& dir, const ResultsTable& table,
                                               Style style = Style::screen);

}  // namespace stiffpath::report
