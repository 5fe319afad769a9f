// The steps of tracing one side of a mark: its sections laid out, a rough pass, paper levels, the centroid pass, outliers; not installed.
#pragma once

#include <string>
#include <vector>

#include "cross_section.hpp"

namespace stiffpath::vision::detail {

//! Across-position b where `line` crosses the middle of section a.
inline double across_on_line(const SectionFrame& frame, const evaluation::Line2& line, double a) {
  return frame.b_of(line.at((a - frame.a_of(line.origin)) / frame.a_of(line.direction)));
}

//! Side `index` of `path` cut into sections along the image axis nearer its normal: body sections from a
//! corner's trim (less a little, so the metrics can trim again at the measured corner) or a cut short of
//! a rough free end, and beyond each free end sections that reach past the mark's tip. Adds a warning for a
//! corner so sharp that the sections must stop farther from it than the trim. Throws stiffpath::Error when
//! the body is too short or the end sections would reach past the image.
SideSections lay_out_sections(const cv::Mat& grey, const CoarseGrid& grid, const CoarsePath& path, std::size_t index,
                              double px_per_m, const ScanOptions& options, std::vector<std::string>& warnings);

//! What the first pass tells about the mark.
struct RoughProfile {
  double extent_px = 0;      //!< the mark's extent along a section (px): its darkness integral over its core darkness
  double core_darkness = 0;  //!< median darkness at the sections' centres
};
//! First pass over the body sections: each centre from the side's own coarse cells, refined by centroids
//! on the coarse paper level. Throws stiffpath::Error for a mark too faint to measure.
RoughProfile centre_roughly(SideSections& side, const evaluation::Line2& line, double coarse_extent_px,
                            double rough_half_window_px, const ScanOptions& options);

//! Paper level of every section not crowded by another side, from the medians of its two flanks just
//! outside the integral's window, averaged along the side. Sections beyond the body (the free ends) are
//! centred on the end's own local line.
void measure_paper_levels(SideSections& side, const evaluation::Line2& low_line, const evaluation::Line2& high_line);

//! Second pass over the body: centroids in a window of ±centroid_half_window_px, darkness integrals and
//! profile spreads in the wide window; from them the mark's full darkness and blur, and each section's
//! width. Returns whether a window was cut short by the image's border.
bool measure_sections(SideSections& side, double centroid_half_window_px);

//! Flags as rejected the body sections whose width is far from the median (dust on the mark, gaps) or whose
//! centre is off its neighbours'; returns how many.
std::size_t reject_outliers(SideSections& side, const evaluation::Line2& line);

}  // namespace stiffpath::vision::detail
