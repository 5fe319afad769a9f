// Cross-sections of the mark along one image axis: pixel access in a side's (along, across) frame, windowed sums.
#pragma once

#include <functional>
#include <optional>

#include "scan_internal.hpp"

namespace stiffpath::vision::detail {

//! A side's section frame: sections are image columns (a = x, b = y) when the side runs closer to
//! x, else rows (a = y, b = x). Section a covers a ∈ [a, a + 1); pixel b covers [b, b + 1).
struct SectionFrame {
  const cv::Mat* grey = nullptr;
  bool columns = true;

  [[nodiscard]] int size_a() const { return columns ? grey->cols : grey->rows; }
  [[nodiscard]] int size_b() const { return columns ? grey->rows : grey->cols; }
  [[nodiscard]] float at(int a, int b) const { return columns ? pixel(*grey, b, a) : pixel(*grey, a, b); }
  [[nodiscard]] Point2 xy(double a, double b) const { return columns ? Point2{a, b} : Point2{b, a}; }
  [[nodiscard]] double a_of(const Point2& p) const { return columns ? p.x() : p.y(); }
  [[nodiscard]] double b_of(const Point2& p) const { return columns ? p.y() : p.x(); }
};

//! Paper level at across-position b (pixel centre) of the current section.
using Paper = std::function<double(double b)>;

//! Darkness sums over the window [lo, hi] of section a, pixels weighted by their overlap with the
//! window (so the window moves continuously with its bounds).
struct WindowSums {
  double mass = 0;     //!< Σ f·d: darkness integral (px)
  double moment = 0;   //!< Σ f·d·b: first moment
  double moment2 = 0;  //!< Σ f·d·b²: second moment
  bool clipped = false;  //!< the window reached past the image
  [[nodiscard]] double centroid(double fallback) const { return mass > 1e-9 ? moment / mass : fallback; }
  //! Variance of the darkness profile about its centroid (px²).
  [[nodiscard]] double variance() const { return mass > 1e-9 ? moment2 / mass - (moment / mass) * (moment / mass) : 0.0; }
};
WindowSums window_sums(const SectionFrame& frame, int a, double lo, double hi, const Paper& paper);
//! The window [c − h, c + h].
inline WindowSums centred_sums(const SectionFrame& frame, int a, double c, double h, const Paper& paper) {
  return window_sums(frame, a, c - h, c + h, paper);
}

//! Darkness of the pixel holding b.
double core_darkness(const SectionFrame& frame, int a, double b, const Paper& paper);

//! Median grey value of pixels [lo, hi) of section a inside the image; nullopt if none.
std::optional<double> flank_median(const SectionFrame& frame, int a, int lo, int hi);

//! Running mean over ±half_window entries of the values present (for the flank levels).
std::vector<std::optional<double>> running_mean(const std::vector<std::optional<double>>& v, int half_window);

//! One cross-section of a side.
struct Section {
  int a = 0;
  bool body = false;     //!< on the full-width part of the side (not in a free end's region)
  double centre = 0;     //!< sub-pixel centre (across, px)
  double mass = 0;       //!< darkness integral over the wide window (px)
  double core = 0;       //!< darkness at the centre
  double width = 0;      //!< perpendicular width (px)
  std::optional<double> lo, hi;  //!< paper levels (grey) of the two flanks, averaged along the side
  double lo_pos = 0, hi_pos = 0; //!< across positions of the flanks' centres
  bool rejected = false;
  bool crowded = false;  //!< another side of the mark is within the section's reach (near a corner): not measured
};

//! The cross-sections of one side, and what they tell about the mark.
struct SideSections {
  SectionFrame frame;
  const CoarseGrid* grid = nullptr;
  const CoarsePath* path = nullptr;      //!< the mark's sides and the cells each owns
  const ScanTuning* tuning = nullptr;
  int side = 0;                          //!< this side's index in path
  std::vector<Section> sections;         //!< consecutive a from `first` to `last`
  int first = 0, body_first = 0, body_last = 0, last = 0;
  bool low_free = false, high_free = false;  //!< the low-a / high-a end of the side is a free end (not a corner)
  double cos_t = 1, tan_t = 0;           //!< angle between the side and the section's along axis
  double window_half_px = 0;             //!< half window of the darkness integrals (px)
  double blur_px = 0;                    //!< σ of the edge blur, perpendicular to the side (px)
  double darkness = 0;                   //!< full darkness of the mark (its core's, corrected for blur)
  double core_factor = 1;                //!< core darkness / full darkness (< 1 when blur reaches the core)
  std::size_t end_fit_sections = 20;     //!< sections used for a free end's local line, width and darkness
  std::size_t crowded_elsewhere = 0;     //!< body sections left out away from corners: another side of the mark was within reach
  [[nodiscard]] Section& at(int a) { return sections[static_cast<std::size_t>(a - first)]; }
  [[nodiscard]] const Section& at(int a) const { return sections[static_cast<std::size_t>(a - first)]; }
};

//! Slope db/da of the centre line at section a: a least-squares line through the accepted body
//! centres within ±ScanTuning::slope_half_window_sections (0 when fewer than three).
double local_slope(const SideSections& side, int a);

//! Flags the body sections whose window or flanks (`reach_px` either side of the centre) hold a pixel
//! darker than `dark` in a coarse cell of another side of the path (two sides running close together
//! near a corner, or the path crossing or touching itself) and takes them out of the body. Throws
//! stiffpath::Error when such sections run on from a corner farther than the metrics' corner trim:
//! the side cannot be measured as far into the corner as the trim asks.
void drop_crowded_sections(SideSections& side, const CoarseSide& coarse, double reach_px, double dark, double px_per_m,
                           const ScanOptions& options);

//! Paper level of a section: linear between its flanks, or the coarse grid's when it has none.
Paper section_paper(const SideSections& side, const Section& s);

//! TLS line through the `count` accepted body centres nearest the low-a or high-a end.
evaluation::Line2 end_line(const SideSections& side, bool low, std::size_t count);

//! A free end of a side: the path's farthest point along the side (the centre of the round spot there)
//! and whether the footprint's tip looks like a round spot's.
struct FreeEnd {
  Point2 cap{0, 0};
  double radius = 0;  //!< fitted radius of the tip's edge (px)
  double rms = 0;     //!< rms misfit of the tip, relative to the mark's darkness
  bool round = true;
  double uncertainty_px = 0;  //!< bound on the error of cap along the side when the end is not round (px)
  bool continues = false;     //!< the mark goes on past the search region: this is not a free end
};
//! `side_line` is the side's fitted line; the end is measured along its direction.
FreeEnd measure_free_end(const SideSections& side, const evaluation::Line2& side_line, bool low);

}  // namespace stiffpath::vision::detail
