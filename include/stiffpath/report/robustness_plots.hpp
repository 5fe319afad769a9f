// The robustness sweep's figure: worst AT_p per condition and compensation, one panel per motion.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "stiffpath/simulation/robustness.hpp"

namespace stiffpath::report {

//! Writes robustness_<motion>.tsv (condition label, then the worst AT_p in µm of each compensation) and
//! renders robustness_<motion> (SVG + PNG) per motion. Returns the figure names. Throws stiffpath::Error
//! when gnuplot fails.
std::vector<std::string> write_robustness_figures(const std::filesystem::path& dir,
                                                  const std::vector<simulation::RobustnessRow>& rows);

}  // namespace stiffpath::report
