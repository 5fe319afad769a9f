// The page on a scanner's bed, for the banded image maker: per-row page share, paper and lid factors, smudges; not installed.
#pragma once

#include <vector>

#include "render_internal.hpp"

namespace stiffpath::vision::detail {

//! One image row of the sheet model.
struct SheetRow {
  std::vector<float> page;   //!< the page's share of each pixel (0 lid .. 1 paper), its edge blurred
  std::vector<float> paper;  //!< factor of the paper's brightness: its curl near the edge, smudges
  std::vector<float> lid;    //!< brightness of the lid there (fraction of full scale), with the page's shadow
};
//! Fills `row` for image row y; `smudge` is that row of the band's smudge darkness (or null).
void sheet_row(const Sheet& sheet, int y, int cols, const float* smudge, SheetRow& row);

//! Adds the sheet's smudges to `band` (CV_32F darkness, image rows y0 … y0 + rows − 1).
void draw_smudges(const Sheet& sheet, int y0, cv::Mat& band);

//! `count` smudges at random places of the page (1–5 mm across, elongated, 2–8 % dark).
std::vector<Smudge> scatter_smudges(const Sheet& sheet, int count, cv::RNG& rng);

}  // namespace stiffpath::vision::detail
