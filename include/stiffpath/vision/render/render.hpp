// Synthetic scans of laser-marked paths with their ground truth: for tests, and to turn a simulated path into a scan.
#pragma once

#include <Eigen/LU>
#include <cstdint>
#include <functional>
#include <optional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/path_metrics.hpp"
#include "stiffpath/vision/scan/fiducials.hpp"

namespace stiffpath::vision {

using evaluation::Point2;

//! The renderer's budget, checked before any work: an image of at most this many pixels ...
inline constexpr double kMaxRenderPixels = 200e6;
//! ... and paths of at most this many points in all (a path is sampled every 20 µm, or every λ/100 of a
//! wiggle; a 150 mm line is 7 500 points). Beyond either, stiffpath::Error names the budget.
inline constexpr std::size_t kMaxRenderPathPoints = 5'000'000;

//! A decaying vibration across the path, like the marks of thesis fig. 4.12:
//! offset(s) = A·e^(−s/τ)·sin(2π s/λ) along the path's arc length s, perpendicular to the path.
struct Wiggle {
  double amplitude_m = 0;        //!< A (m); 0 = a clean path
  double wavelength_m = 10e-3;   //!< λ (m)
  double decay_length_m = 40e-3; //!< τ (m)
};

//! The nominal path to mark: vertices in m (x right, y down, as on the scan), sides between them.
struct PathShape {
  std::vector<Point2> vertices;  //!< for a closed shape the first vertex is not repeated
  bool closed = false;
};

//! A straight line of `length_m` along +x.
PathShape line_shape(double length_m);
//! An equilateral triangle of side `side_m` with a horizontal base, apex up on screen, vertices from the
//! bottom-left one clockwise on screen (closed).
PathShape triangle_shape(double side_m);

//! How the scan looks. Defaults resemble a 1200 dpi office scan of a laser mark on coated chipboard.
struct RenderOptions {
  double dpi = 1200;              //!< resolution of the image (dots per inch)
  double mark_width_m = 0.2e-3;   //!< diameter of the laser spot = width of the mark (m)
  double rotation_rad = 0;        //!< rotation of the path (rad); positive turns x towards y, clockwise on screen (y down)
  double margin_m = 2e-3;         //!< paper around the mark on every side (m)
  double blur_px = 0.8;           //!< σ of the scanner's Gaussian blur (px); 0 = none
  double noise = 0.01;            //!< σ of white pixel noise (fraction of full scale)
  double texture = 0.01;          //!< σ of the wood-fibre texture of the paper (fraction of its brightness)
  double shading = 0.08;          //!< illumination falloff across the image, peak to peak (fraction)
  double paper_level = 0.88;      //!< paper brightness (fraction of full scale)
  double ink_level = 0.22;        //!< brightness of a fully marked pixel on paper of paper_level
  int specks = 0;                 //!< dust specks (dark dots of 1–4 px radius) scattered over the image
  int bit_depth = 8;              //!< 8 or 16
  bool colour = false;            //!< three-channel BGR image (a warm paper tone) instead of grey
  std::uint64_t seed = 1;         //!< seed of every random choice (noise, texture, specks)
  //! Metrics options of the ground truth; by default an interpolating spline (exact for the dense path).
  evaluation::PathMetricsOptions truth_options{0.0};
  //! Called after each band of rows with the fraction of the image made (0..1); may be empty.
  std::function<void(double)> progress;
};

//! A rendered scan and what is known about it.
struct RenderedScan {
  cv::Mat image;                                   //!< CV_8U/CV_16U, one or three channels
  double dpi = 1200;
  double mark_width_m = 0;
  std::vector<std::vector<Point2>> sides;          //!< the marked centre path per side, image frame (m)
  bool closed = false;
  evaluation::PathMetrics truth;                   //!< metrics of the exact centre path (evaluation module)
};

//! Densely samples a shape (points at most `step_m` apart, and ≤ λ/100 with a wiggle), adding the
//! wiggle along the whole path. One point list per side; consecutive sides share their corner. Throws
//! stiffpath::Error, before sampling, for a path that would take more than kMaxRenderPathPoints points.
std::vector<std::vector<Point2>> sample_shape(const PathShape& shape, const Wiggle& wiggle, double step_m = 20e-6);

//! Resamples a path given by points in marking order (m) at equal arc-length steps of at most
//! `step_m`, keeping its first and last point. A path sampled in time (a simulated mark) is dense
//! where the spot moves slowly; resampled, every part of it weighs by its length in the metrics, as
//! the cross-sections of a scan do. Throws stiffpath::Error for fewer than two distinct points, and, before
//! resampling, for a path that would take more than kMaxRenderPathPoints points.
std::vector<Point2> resample_path(const std::vector<Point2>& points, double step_m = 20e-6);

//! Receives a rendered image band by band, top to bottom: `rows` (CV_8U/CV_16U, one or three
//! channels, the image's full width) are the image's rows first_row … first_row + rows.rows − 1.
using RowSink = std::function<void(int first_row, const cv::Mat& rows)>;

//! Renders sides (points in m, any frame): rotates them, places them `margin_m` inside an image
//! just large enough, draws the mark as every point within mark_width/2 of the path (a round
//! laser spot: round ends) with area-sampled anti-aliasing, then blur, paper texture, shading,
//! noise and specks. The truth is evaluation::measure_sides on the placed path. The image is made
//! in bands of rows, so its working memory is a few bands besides the image itself. Throws
//! stiffpath::Error for invalid options or an image above 200 Mpx.
RenderedScan render_scan(const std::vector<std::vector<Point2>>& sides, bool closed, const RenderOptions& options);

//! The size (px) of the image render_scan makes of these sides with these options.
cv::Size rendered_size(const std::vector<std::vector<Point2>>& sides, const RenderOptions& options);

//! The same, handing the image to `sink` band by band instead of keeping it (RenderedScan::image is
//! left empty): with a streaming writer the image is never held whole in memory.
RenderedScan render_scan(const std::vector<std::vector<Point2>>& sides, bool closed, const RenderOptions& options,
                         const RowSink& sink);

//! One mark on a plate: its path in the plate's frame (m, x right and y down from the page's top-left
//! corner), one point list per side as sample_shape gives them.
struct PlateMarkPath {
  std::vector<std::vector<Point2>> sides;
  bool closed = false;
  std::string id{};  //!< the mark's name in the plate file (may be empty), given back with its truth
  SourceLocation where{};  //!< where the plate file describes it ("marks[2]" at file:line:column), for errors; may be empty
};

//! A fiducial on a plate: a ring (and cross) marked slowly, centred at `at_m` (page frame).
struct PlateFiducial {
  Point2 at_m{0, 0};
  FiducialShape shape;
  SourceLocation where{};  //!< where the plate file describes it, for errors; may be empty
};

//! How the page lies on a scanner's bed and what the scanner sees around it. The image is the bed; the
//! page is placed with its top-left corner at page_at_m and turned by page_angle_rad about that corner,
//! and the scan may come out mirrored. Around the page the lid shows; along the page's edge a thin shadow,
//! inside it the paper darkens where it lifts off the glass; smudges lie on the paper.
struct ScannerBed {
  double width_m = 0.216, height_m = 0.297;  //!< the bed, and so the image (m)
  Point2 page_at_m{0, 0};                   //!< the page's top-left corner on the bed (m)
  double page_angle_rad = 0;                //!< the page's rotation about that corner (rad, clockwise on screen)
  bool mirror = false;                      //!< the scan is mirrored left to right (x → width − x)
  double lid_level = 0.97;                  //!< brightness of the lid around the page (fraction of full scale)
  double edge_shadow = 0.3;                 //!< darkness of the shadow along the page's edge (fraction of the lid's)
  double edge_shadow_m = 0.15e-3;           //!< its width (m)
  double curl_m = 3e-3;                     //!< the paper darkens within this distance of its edge (m) ...
  double curl_shading = 0.05;               //!< ... by this fraction at the edge, fading quadratically inwards
  int smudges = 0;                          //!< soft grey smudges on the paper: 1–5 mm across, 2–8 % darker
};

//! Where a page point lands on the image: image = offset + linear · page (m).
struct PagePlacement {
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Point2 offset{0, 0};
  [[nodiscard]] Point2 apply(const Point2& page) const { return offset + linear * page; }
  [[nodiscard]] bool mirrored() const { return linear.determinant() < 0; }
};
//! The placement a bed gives (identity without a bed: the page is the image).
PagePlacement page_placement(const ScannerBed* bed);

//! Lettering on a plate, engraved with strokes as wide as the marks (OpenCV's Hershey simplex font).
struct PlateLabel {
  std::string text;
  Point2 at_m{0, 0};        //!< bottom-left corner of the text (m, page frame)
  double height_m = 4e-3;   //!< height of a capital letter (m)
  SourceLocation where{};     //!< where the plate file describes it, for errors; may be empty
};

//! A page holding several marks, fiducials and labels, as a lab scans it.
struct Plate {
  double width_m = 0.210, height_m = 0.297;  //!< page size (m); A4 by default
  std::vector<PlateMarkPath> marks;
  std::vector<PlateLabel> labels;
  std::vector<PlateFiducial> fiducials;
  //! The scanner's bed the page lies on; without one the image is the page, edge to edge.
  std::optional<ScannerBed> bed;
};

//! The ground truth of one mark of a rendered plate.
struct PlateMarkTruth {
  std::string id;                          //!< the mark's id in the plate file
  std::vector<std::vector<Point2>> sides;  //!< its centre path per side (m, image frame)
  bool closed = false;
  evaluation::PathMetrics truth;           //!< evaluation::measure_sides on that path
  cv::Rect2d box_m;                        //!< bounding box of the path (m), not counting the mark's width
};

//! A rendered plate: the image (one pixel per dpi step of the page, or of the bed) and each mark's truth.
struct RenderedPlate {
  cv::Mat image;  //!< empty when rendered into a RowSink
  double dpi = 1200;
  double mark_width_m = 0;
  std::vector<PlateMarkTruth> marks;
  std::vector<Point2> fiducials_m;  //!< each fiducial's centre (m, image frame), in the plate's order
  PagePlacement placement;          //!< where the page lies in the image
  cv::Size size_px;                 //!< the image's size
};

//! The size (px) of the image render_plate makes of this plate.
cv::Size plate_image_size(const Plate& plate, const RenderOptions& options);

//! Renders a plate like render_scan renders one path (options.rotation_rad and margin_m are not used:
//! the page, or the bed it lies on, is the image). Throws stiffpath::Error for a mark, fiducial or label
//! outside the page or the image, invalid options, or a plate beyond the budget (kMaxRenderPixels,
//! kMaxRenderPathPoints).
RenderedPlate render_plate(const Plate& plate, const RenderOptions& options);
//! The same into a RowSink.
RenderedPlate render_plate(const Plate& plate, const RenderOptions& options, const RowSink& sink);

//! Draws the coverage (0..1, area fraction of each pixel within `radius_px` of the polyline given in
//! pixel units) into `coverage` (CV_32F), keeping the larger value where something is already drawn.
void draw_stroke_coverage(cv::Mat& coverage, const std::vector<Point2>& polyline_px, double radius_px);

}  // namespace stiffpath::vision
