// Internal stages of the synthetic scanner: the scene in pixels, the stroke rasteriser and the banded image maker; not installed.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "stiffpath/vision/render/render.hpp"

namespace stiffpath::vision::detail {

//! Area-sampled coverage of round-capped strokes (every point within `radius` px of a polyline),
//! drawn into any band of rows of the image.
class StrokeRaster {
 public:
  StrokeRaster(const std::vector<std::vector<Point2>>& polylines_px, double radius_px);
  //! Draws into `coverage` (CV_32F, the image's width) holding image rows row0 … row0 + rows − 1,
  //! keeping the larger value where something is already drawn.
  void draw(cv::Mat& coverage, int row0) const;

 private:
  struct Segment {
    Point2 a, d;  // start and direction·length (px)
    double inv_len2;
  };
  std::vector<Segment> segments_;
  std::vector<std::pair<double, double>> rows_;  // y range of each segment, widened by the radius
  double radius_;
};

//! A soft grey smudge on the paper: darkness strength·exp(−(u²/a² + v²/b²)/2) in its own axes (image px).
struct Smudge {
  Point2 centre{0, 0};
  double sigma_a = 1, sigma_b = 1, angle_rad = 0, strength = 0;
};

//! The page on a scanner's bed, in image pixels: where it lies and what surrounds it.
struct Sheet {
  Eigen::Matrix2d to_page = Eigen::Matrix2d::Identity();  //!< page px = to_page · (image px − origin_px)
  Point2 origin_px{0, 0};                                //!< the page's top-left corner (image px)
  double width_px = 0, height_px = 0;                    //!< the page's size (px)
  double edge_blur_px = 0.5;                             //!< σ of the page edge's step (the scanner's blur and the pixel)
  ScannerBed bed;                                        //!< levels, shadow and curl (shadow and curl widths in m)
  double px_per_m = 0;
  std::vector<Smudge> smudges;
};

//! What the synthetic scanner draws, in image pixels.
struct Scene {
  int rows = 0, cols = 0;
  std::vector<std::vector<Point2>> strokes_px;  //!< each mark's path as one polyline
  double radius_px = 0;                         //!< half the mark's width
  struct Text {
    std::string text;
    Point2 at_px{0, 0};  //!< bottom-left of the text
    double height_px = 0;
  };
  std::vector<Text> labels;  //!< upright labels drawn straight into the image
  //! Labels drawn upright beside the image and then turned (or mirrored) onto it: coverage at `at` (image px).
  struct Sprite {
    cv::Mat coverage;  //!< CV_32F
    cv::Point at;
  };
  std::vector<Sprite> sprites;
  std::optional<Sheet> sheet;  //!< the page on a bed; none: the image is all paper
};

//! Throws stiffpath::Error for options out of range.
void check_render_options(const RenderOptions& options);
//! Throws stiffpath::Error when an image of this size (px) is above the kMaxRenderPixels budget.
void check_image_size(double width_px, double height_px);
//! Throws stiffpath::Error when `points` path points would exceed the kMaxRenderPathPoints budget; `what` names them.
void check_path_points(double points, const std::string& what);

//! The label's text drawn upright as coverage (CV_32F) with strokes `thickness` px wide, its bottom-left
//! corner at `origin` within the returned image.
cv::Mat label_coverage(const Scene::Text& label, int thickness, cv::Point& origin);

//! Makes the image of a scene in bands of rows, top to bottom, handing each band to `sink`: coverage
//! of the strokes and labels, blur, specks, paper texture, shading, noise, quantisation.
void rasterise(const Scene& scene, const RenderOptions& options, const RowSink& sink);

//! Rasterises into one image (the sink copying each band into it).
cv::Mat rasterise_image(const Scene& scene, const RenderOptions& options);

}  // namespace stiffpath::vision::detail
