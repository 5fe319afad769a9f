// Internal stages of the synthetic scanner: the scene in pixels, the stroke rasteriser and the banded image maker; not installed.
#pragma once

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
  std::vector<Text> labels;
};

//! Throws stiffpath::Error for options out of range.
void check_render_options(const RenderOptions& options);
//! Throws stiffpath::Error when an image of this size (px) is above the 200 Mpx limit.
void check_image_size(double width_px, double height_px);

//! Makes the image of a scene in bands of rows, top to bottom, handing each band to `sink`: coverage
//! of the strokes and labels, blur, specks, paper texture, shading, noise, quantisation.
void rasterise(const Scene& scene, const RenderOptions& options, const RowSink& sink);

//! Rasterises into one image (the sink copying each band into it).
cv::Mat rasterise_image(const Scene& scene, const RenderOptions& options);

}  // namespace stiffpath::vision::detail
