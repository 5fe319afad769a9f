// Internal helpers of the side finder: sequential RANSAC lines and the cells' assignment to them; not installed.
#pragma once

#include <vector>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

//! A straight side found among the mark's cells: its line and its extent t0 ≤ t ≤ t1 along it (px).
struct FoundSide {
  evaluation::Line2 line;
  double t0 = 0, t1 = 0;
};

//! Tolerances of the search (px).
struct SideSearch {
  double band = 0;        //!< a cell is on a line when its offset is at most this
  double max_gap = 0;     //!< longest gap along a side
  double min_length = 0;  //!< shortest side
};

//! Weighted TLS line through the cells `idx` of the mark and their extent along it.
FoundSide fit_cells(const MarkComponent& mark, const std::vector<std::size_t>& idx);

//! `n` sides by sequential RANSAC (600 seeded trials each; the heaviest gap-free run of cells within
//! the band, refitted three times). Throws stiffpath::Error when fewer than n sides are found or more
//! than 15 % of the mark's darkness lies on none of them.
std::vector<FoundSide> ransac_sides(const MarkComponent& mark, int n, const SideSearch& search, const SourceLocation& where);

//! Gives every cell of the mark to the side whose segment [t0, t1] is nearest, then sets each side's
//! extent to that of its cells, and repeats until the extents settle: a side whose ends bend away from
//! its line (a robot that decelerates into a corner) is followed to its corner. Returns the side of
//! each cell.
std::vector<int> assign_cells(const MarkComponent& mark, std::vector<FoundSide>& sides);

}  // namespace stiffpath::vision::detail
