// The scan analysis's tuning constants in one place, each named with its unit (px of the scan, coarse cells, m, fractions).
#pragma once

#include <cstddef>
#include <cstdint>

namespace stiffpath::vision {

//! How the scan analysis finds and measures a mark (docs/vision.md, "Pipeline", names each step). The defaults
//! are what the accuracy figures in docs/vision.md were measured with; a lab changes them only to study the
//! method. "px" is a pixel of the scan, a "cell" a cell of the coarse grid, w the mark's rough width.
struct ScanTuning {
  // --- Coarse grid and dark features (coarse_grid.cpp, find_mark.cpp) ---
  int cell_px = 4;                           //!< side of a coarse grid cell (px)
  int paper_block_cells = 16;                //!< the paper level is the median of blocks this many cells a side
  std::size_t paper_sample_cells = 1000000;  //!< most cells sampled for the paper's darkness level and noise
  double dark_noise_sigmas = 6.0;            //!< a cell is dark above the paper's darkness + this many σ of its noise ...
  double dark_min_darkness = 0.04;           //!< ... and at least this much darker than the paper (fraction)
  double second_mark_ratio = 0.2;            //!< a second feature this large against the mark's extent is a second mark
  double full_darkness_quantile = 0.9;       //!< the darkness of a mark's fully covered cells: this quantile of its cells'
  double edge_step = 0.02;                   //!< a feature with the paper beyond it brighter on one side by more (fraction, and
                                             //!< more than the noise) is the paper's edge on the lid, not a mark
  int edge_reach_cells = 48;                 //!< the paper beyond a feature is looked for within this many cells of it
  double max_mark_width_m = 1e-3;            //!< a feature wider than this (m) is a smudge or a shadow, not a laser mark

  // --- Sides on the coarse grid (find_sides.cpp, ransac_sides.cpp, assign_cells.cpp) ---
  double side_band_cells = 1.5;       //!< a cell is on a side within w/2 + this many cells of its line
  double widest_band_m = 1e-3;        //!< for sides that bow the band doubles, up to max(widest_band_m, widest_band_widths·w) (m)
  double widest_band_widths = 3.0;    //!< (in widths w)
  double side_gap_m = 1e-3;           //!< a side has no gap longer than max(side_gap_m, side_gap_widths·w) (m)
  double side_gap_widths = 3.0;       //!< (in widths w)
  double straightness_m = 1e-3;       //!< a side strays at most max(straightness_m, straightness_fraction·length) + w (m)
  double straightness_fraction = 0.03;  //!< (of the side's length)
  double corner_reach_m = 2e-3;       //!< side ends link where their lines meet within max(corner_reach_m, corner_reach_widths·w) (m)
  double corner_reach_widths = 4.0;   //!< (in widths w)
  double parallel_rad = 0.17;         //!< sides closer to parallel than this never meet at a corner (rad)
  int ransac_trials = 600;            //!< random line candidates per side
  std::uint64_t ransac_seed = 7;      //!< seed of the candidates (the result is reproducible)
  double unassigned_fraction = 0.15;  //!< more of the mark's darkness on no side means more sides than asked
  int assign_iterations = 30;         //!< most rounds of giving cells to the nearest side segment
  double assign_settle_px = 0.5;      //!< the rounds stop when no segment end moves farther (px)

  // --- Cross-sections of a side (side_sections.cpp, section_centres.cpp, section_outliers.cpp) ---
  double window_margin_px = 4.0;        //!< the darkness integral's half window: the mark's half extent + this (covers the blur)
  int flank_px = 5;                     //!< paper pixels on each side of a section for its paper level
  int paper_window_sections = 31;       //!< sections whose flank levels are averaged into one section's paper level
  double coarse_window_extra_px = 2.0;  //!< the first pass's half window: the coarse half extent + window margin + this
  double corner_clearance_px = 4.0;     //!< sections near a corner keep this much clear of the other side beyond their flanks
  double min_corner_sine = 0.1;         //!< sharper corners are treated as this sine (so the clearance stays bounded)
  double corner_approach_cells = 3.0;   //!< sections start this many cells or ...
  double corner_approach_m = 0.15e-3;   //!< ... this far (m), whichever is more, closer to a corner than the corner trim
  double end_cut_widths = 0.6;          //!< body sections stop this many w (+ a cell + end_cut_px) short of a rough free end
  double end_cut_px = 1.5;              //!< (px)
  double end_reach_px = 2.0;            //!< end sections reach this far (+ margin + a cell) beyond a rough free end (px)
  double min_body_px = 10.0;            //!< a side whose body is shorter is too short to measure (px)
  double rough_window_px = 3.0;         //!< first centroid's half window beyond the coarse half extent (px) ...
  double rough_refine_px = 2.0;         //!< ... then the refinements' (px)
  int rough_refinements = 2;            //!< refinements of the first pass's centroid
  double min_mark_darkness = 0.03;      //!< a fainter mark is refused (fraction)
  double centroid_margin_px = 1.0;      //!< the centroid's half window: the mark's half extent + this (px)
  int centroid_iterations = 3;          //!< iterations of the centroid in its window
  double end_fit_m = 1.5e-3;            //!< a free end's local line, width and darkness come from this stretch (m) ...
  std::size_t end_fit_min_sections = 20;  //!< ... and at least this many sections
  double crowding_darkness_ratio = 1.0 / 3;  //!< another side's pixel this dark (of the mark's) crowds a section
  double crowded_run_gap_cells = 2.0;   //!< crowded sections closer together (cells) run on from the corner as one
  int blur_solve_iterations = 30;       //!< fixed-point iterations for the mark's full darkness and blur
  double min_blur_variance_px2 = 0.01;  //!< floor of the blur's variance in that solve (px²)
  double min_core_erf = 0.2;            //!< floor of the core's fraction of full darkness in that solve
  int slope_half_window_sections = 8;   //!< the centre line's local slope: a line through ± this many sections
  std::size_t min_sections = 10;        //!< fewer usable sections on a side: refused
  double width_tolerance = 0.15;        //!< a section whose width is off the median by more (fraction) is an outlier ...
  double outlier_mads = 6.0;            //!< ... or by more than this many robust σ (from the median absolute deviation)
  int outlier_neighbours = 10;          //!< a centre is compared with its neighbours within ± this many sections ...
  double min_centre_tolerance_px = 0.5;  //!< ... and is an outlier off their line by more than this (px) and outlier_mads σ

  // --- Free ends (trace_end.cpp, end_tip_seed.cpp, end_tip_fit.cpp) ---
  double tip_threshold_ratio = 0.5;    //!< the tip's footprint: pixels darker than this fraction of the core's darkness
  double tip_box_margin_px = 2.0;      //!< the tip's search box: the side's cells beyond the seed, widened by w + margin + this (px)
  double tip_half_angle_deg = 50.0;    //!< the round-spot fit uses the edge within this angle of the side's direction (deg)
  double round_tip_max_rms = 0.06;     //!< a round end's fit misfits by at most this (of the mark's darkness) ...
  double round_tip_min_radius = 0.75;  //!< ... with a radius between these multiples of w/2
  double round_tip_max_radius = 1.5;   //!< (of w/2)
};

}  // namespace stiffpath::vision
