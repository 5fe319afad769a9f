// ISO 9283:1998 §7.7 path accuracy AT_p and path repeatability RT_p of attained paths against a commanded path.
#pragma once

#include <span>
#include <vector>

#include "stiffpath/evaluation/line_fit.hpp"

namespace stiffpath::evaluation {

//! Path accuracy and repeatability in the planes normal to the commanded path (2-D: normal lines).
struct PathAccuracy {
  double accuracy_m = 0;       //!< AT_p = maxᵢ |x̄ᵢ − cᵢ|: the barycentre of the runs' crossings x̄ᵢ against the command cᵢ
  double repeatability_m = 0;  //!< RT_p = maxᵢ (l̄ᵢ + 3·S_lᵢ), lᵢⱼ = |xᵢⱼ − x̄ᵢ|; 0 for a single run
  std::size_t planes_requested = 0;  //!< normal planes asked for
  std::size_t planes_used = 0;       //!< planes every run crossed (the others are skipped)
  std::vector<double> arc_length_m;  //!< position of each used plane along the command (m)
  std::vector<double> deviation_m;   //!< |x̄ᵢ − cᵢ| at each used plane (m)
};

//! Evaluates `runs` (attained paths, points in m in the order marked) against the commanded
//! polyline `command` at `planes` normal lines evenly spaced along it (at arc lengths (i + ½)·S/m).
//! Each run's crossing with a normal line is the one nearest the command point. Throws
//! stiffpath::Error for a command shorter than two distinct points, no runs, or no usable plane.
PathAccuracy iso9283_path_accuracy(std::span<const Point2> command, const std::vector<std::vector<Point2>>& runs,
                                   std::size_t planes = 100);

}  // namespace stiffpath::evaluation
