// Internal steps of the scan analysis (coarse grid, mark finding, sides, cross-sections); not installed.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/evaluation/line_fit.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision::detail {

//! Grey value of an 8- or 16-bit single-channel image.
inline float pixel(const cv::Mat& m, int row, int col) {
  return m.depth() == CV_8U ? static_cast<float>(m.ptr<std::uint8_t>(row)[col])
                            : static_cast<float>(m.ptr<std::uint16_t>(row)[col]);
}

//! The image averaged over cell × cell blocks, the paper level and the darkness 1 − mean/paper.
struct CoarseGrid {
  int cell = 4;         //!< side of a cell (px)
  int block_cells = 16;  //!< side of a paper-level block (cells)
  cv::Mat darkness;  //!< CV_32F, ceil(rows/cell) × ceil(cols/cell)
  //! Paper level: the median grey of each block of block_cells² cells (CV_32F), between whose centres it is
  //! interpolated bilinearly (kept at this resolution: a grid of cells would cost a float per 16 px).
  cv::Mat blocks;
  double median = 0, sigma = 0, threshold = 0;  //!< of darkness over all cells
  cv::Mat mask;                        //!< CV_8U, 1 where darkness > threshold
  //! Paper level at a full-resolution pixel centre, bilinear between cell centres.
  [[nodiscard]] double paper_at(double x_px, double y_px) const;
};
CoarseGrid build_coarse_grid(const cv::Mat& grey, const ScanTuning& tuning);

//! "x = … mm, y = … mm" of a position (px of the analysed image or region) in the scan's frame.
std::string position_text(const Point2& px, double px_per_m, const ScanOptions& options);

//! A connected dark feature of the coarse grid (8-connected cells darker than the threshold).
struct Feature {
  int label = 0;           //!< its label in Features::labels
  double mass = 0;         //!< Σ darkness of its cells
  double extent_px = 0;    //!< diagonal of its bounding box (px)
  cv::Rect box;            //!< bounding box (cells)
  std::string border;      //!< "left", "top", "right", "bottom" if it touches that border, else empty
};
//! Every dark feature, in the order of their top-left-most cells (reading order of their top edges).
struct Features {
  cv::Mat labels;             //!< CV_32S, 0 = paper
  std::vector<Feature> list;  //!< list[i].label == i + 1
};
Features find_features(const CoarseGrid& grid);

//! The cells away from every dark feature (CV_8U, non-zero there): the paper (or the lid) around them.
cv::Mat paper_cells(const CoarseGrid& grid);
//! Why a dark feature is not a laser mark — the paper's edge (the paper beyond it differs from one side to the
//! other by more than ScanTuning::edge_step) or a smudge or shadow (wider than ScanTuning::max_mark_width_m) —
//! or empty when it may be one. `paper` is paper_cells(grid).
std::string paper_artefact(const CoarseGrid& grid, const Features& features, const Feature& feature, const cv::Mat& paper,
                           double px_per_m, const ScanTuning& tuning);

//! A mark: one feature's cells and what they tell about it.
struct MarkComponent {
  int label = 0;                 //!< the feature's label
  std::vector<Point2> cells_px;  //!< centres of its cells (px)
  std::vector<double> weights;   //!< their darkness
  double full_darkness = 0;      //!< darkness of fully covered cells (ScanTuning::full_darkness_quantile of its cells')
  double width_px = 0;           //!< rough width: area / half the contour length
  int specks = 0;
  std::vector<std::string> warnings;
  cv::Rect box;                  //!< bounding box of its cells (cells)
};
MarkComponent mark_of(const CoarseGrid& grid, const Features& features, const Feature& feature, const ScanTuning& tuning);
//! The one mark of a scan: the heaviest feature; a second one of ≥ second_mark_ratio its size, or the mark touching
//! the border, is an error; features under min_mark_length_m are specks.
MarkComponent find_mark(const CoarseGrid& grid, double px_per_m, const ScanOptions& options);

//! A side found on the coarse grid, in px; start and end are corners or rough free ends.
struct CoarseSide {
  evaluation::Line2 line;
  Point2 start{0, 0}, end{0, 0};
  bool start_is_corner = false, end_is_corner = false;
  double start_angle_rad = 0, end_angle_rad = 0;  //!< interior angle at a corner
};
//! Marks a cell that belongs to no side.
inline constexpr std::uint8_t kNoSide = 255;
struct CoarsePath {
  std::vector<CoarseSide> sides;
  bool closed = false;
  double width_px = 0;  //!< the mark's rough width (px)
  cv::Rect box;   //!< the mark's bounding box (cells)
  cv::Mat owner;  //!< CV_8U over `box`: the side (index in `sides`) owning each cell of the mark, else kNoSide
  //! The side owning grid cell (gx, gy), or kNoSide.
  [[nodiscard]] int owner_at(int gx, int gy) const {
    return box.contains(cv::Point(gx, gy)) ? owner.at<std::uint8_t>(gy - box.y, gx - box.x) : kNoSide;
  }
};
CoarsePath find_sides(const MarkComponent& mark, int n_sides, double px_per_m, const ScanOptions& options);

//! Centre line of one side from full-resolution cross-sections (px).
struct SideTrace {
  std::vector<Point2> centres;            //!< accepted body cross-sections, ordered from start to end
  std::vector<double> widths;             //!< their perpendicular widths (px)
  std::optional<Point2> start_cap, end_cap;  //!< estimated path ends (round-spot cap centres) of free ends
  std::size_t sections = 0, rejected = 0;
  double width = 0;                       //!< median width (px)
  double darkness = 0;                    //!< darkness of the mark's core
  double end_uncertainty = 0;             //!< sum of the free ends' error bounds along the side (px; 0 for round ends)
  std::vector<std::string> warnings;
};
//! Side `k` of `path`.
SideTrace trace_side(const cv::Mat& grey, const CoarseGrid& grid, const CoarsePath& path, std::size_t k, double px_per_m,
                     const ScanOptions& options);

//! Checks the image, resolution, options and region; throws stiffpath::Error naming options.label.
void check_scan_input(const cv::Mat& grey, double dpi, const ScanOptions& options);

//! The sides of a mark: options.sides of them, or for 0 the fewest (1..max_auto_sides) that work.
CoarsePath find_path(const MarkComponent& mark, double px_per_m, const ScanOptions& options);

//! Everything analyse_scan measures about one mark of the (region's) image; positions in the whole
//! image's frame. dpi and the image size are left for the caller.
ScanResult measure_mark(const cv::Mat& grey, const CoarseGrid& grid, const MarkComponent& mark, double px_per_m,
                        const ScanOptions& options);

}  // namespace stiffpath::vision::detail
