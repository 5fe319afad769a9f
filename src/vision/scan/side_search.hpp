// Internal helpers of the side finder: sequential RANSAC lines and the cells' assignment to them; not installed.
#pragma once

#include <cstdint>
#include <vector>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

//! A straight side found among the mark's cells: its line and its extent t0 ≤ t ≤ t1 along it (px).
struct FoundSide {
  evaluation::Line2 line;
  double t0 = 0, t1 = 0;
};

//! Tolerances of the search.
struct SideSearch {
  double band = 0;        //!< a cell is on a line when its offset is at most this (px)
  double max_gap = 0;     //!< longest gap along a side (px)
  double min_length = 0;  //!< shortest side (px)
  int trials = 600;       //!< random line candidates per side
  std::uint64_t seed = 7;            //!< seed of the candidates
  double unassigned_fraction = 0.15;  //!< most of the mark's darkness left on no side
};

//! Weighted TLS line through the cells `idx` of the mark and their extent along it.
FoundSide fit_cells(const MarkComponent& mark, const std::vector<std::size_t>& idx);

//! `n` sides by sequential RANSAC (search.trials seeded trials each; the heaviest gap-free run of cells
//! within the band, refitted three times). Throws stiffpath::Error when fewer than n sides are found or
//! more than search.unassigned_fraction of the mark's darkness lies on none of them.
std::vector<FoundSide> ransac_sides(const MarkComponent& mark, int n, const SideSearch& search, const SourceLocation& where);

//! Gives every cell of the mark to the side whose segment [t0, t1] is nearest, then sets each side's
//! extent to that of its cells, and repeats until the extents settle: a side whose ends bend away from
//! its line (a robot that decelerates into a corner) is followed to its corner; at most `iterations`
//! rounds, fewer once no segment end moves more than `settle_px`. Returns the side of each cell.
std::vector<int> assign_cells(const MarkComponent& mark, std::vector<FoundSide>& sides, int iterations, double settle_px);

}  // namespace stiffpath::vision::detail
