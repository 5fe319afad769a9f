// The overlay reads at any aspect ratio and size: captions fit, legend and scale bar are drawn, sides are numbered.
#include <gtest/gtest.h>

#include <algorithm>
#include <fmt/format.h>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "stiffpath/vision/scan/overlay.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {
namespace {

RenderOptions quiet_paper() {
  RenderOptions o;
  o.margin_m = 2e-3;
  return o;
}

bool inside(const cv::Rect& box, const cv::Size& size) { return (box & cv::Rect({0, 0}, size)) == box && !box.empty(); }

// Pixels of `colour` (within 40 per channel) in a region of the picture.
int count_colour(const cv::Mat& bgr, const cv::Rect& region, const cv::Scalar& colour) {
  cv::Mat mask;
  cv::inRange(bgr(region & cv::Rect({0, 0}, bgr.size())), colour - cv::Scalar(40, 40, 40), colour + cv::Scalar(40, 40, 40), mask);
  return cv::countNonZero(mask);
}

// What every overlay must satisfy: text sized to the picture, every text inside it and clear of the
// others, a legend with the four line kinds, a scale bar whose length is its mm at the picture's scale.
void expect_readable(const cv::Mat& picture, const OverlayLayout& layout, double dpi) {
  ASSERT_EQ(picture.type(), CV_8UC3);
  EXPECT_EQ(picture.size(), layout.size);
  // Text about 1/80 of the scan's larger side (at least 14 px, at most 160 px), so it reads when the
  // picture is shown whole.
  const int scan_side = std::max(layout.scan.width, layout.scan.height);
  EXPECT_GE(layout.text_height_px, std::min(160, std::max(14, scan_side / 100)));
  for (const auto& t : layout.texts) EXPECT_TRUE(inside(t.box, picture.size())) << "'" << t.text << "' sticks out: " << t.box;
  for (std::size_t i = 0; i < layout.texts.size(); ++i) {
    for (std::size_t j = i + 1; j < layout.texts.size(); ++j) {
      const cv::Rect overlap = layout.texts[i].box & layout.texts[j].box;
      EXPECT_LT(overlap.area(), layout.text_height_px * layout.text_height_px / 4)
          << "'" << layout.texts[i].text << "' overlaps '" << layout.texts[j].text << "'";
    }
  }
  for (const char* entry : {"centre line", "fitted line", "smoothing spline", "corner"}) {
    EXPECT_NE(std::find(layout.legend_entries.begin(), layout.legend_entries.end(), entry), layout.legend_entries.end()) << entry;
  }
  // The legend's swatches are drawn in their colours, inside the legend.
  EXPECT_GT(count_colour(picture, layout.legend, {60, 170, 60}), 10);   // green
  EXPECT_GT(count_colour(picture, layout.legend, {220, 90, 20}), 10);   // blue
  EXPECT_GT(count_colour(picture, layout.legend, {40, 40, 230}), 10);   // red
  // The scale bar: a dark run along its middle row as long as its mm at this scale.
  ASSERT_GT(layout.scale_bar_mm, 0);
  const double bar_px = layout.scale_bar_mm * 1e-3 * dpi / 0.0254 * layout.scale;
  EXPECT_NEAR(layout.scale_bar.width - 1, bar_px, 1.0);
  const int row = layout.scale_bar.y + layout.scale_bar.height / 2;
  int dark = 0;
  for (int x = layout.scale_bar.x; x < layout.scale_bar.x + layout.scale_bar.width; ++x) {
    const cv::Vec3b p = picture.at<cv::Vec3b>(row, x);
    dark += p[0] < 100 && p[1] < 100 && p[2] < 100 ? 1 : 0;
  }
  EXPECT_GE(dark, layout.scale_bar.width - 2);
  EXPECT_GE(layout.scale_bar.width, picture.cols / 20);  // long enough to read
}

// The case: a vertical 150 mm mark on a scan 215 px wide. Its strip used to be squeezed into
// the image's width and its caption cut to "side 1: deviation x4 (strip".
TEST(Overlay, AVerticalMarkOnANarrowScanGetsAFullStripAndWholeCaption) {
  RenderOptions o = quiet_paper();
  o.rotation_rad = std::numbers::pi / 2;
  const auto scan = render_scan(sample_shape(line_shape(150e-3), {0.05e-3, 10e-3, 40e-3}), false, o);
  ASSERT_LT(scan.image.cols, 250);
  const auto result = analyse_scan(scan.image, scan.dpi, {});
  OverlayLayout layout;
  const cv::Mat picture = draw_overlay(scan.image, result, &layout);
  expect_readable(picture, layout, scan.dpi);
  EXPECT_EQ(layout.scale, 1.0);
  EXPECT_EQ(layout.scan.size(), scan.image.size());  // the scan at true scale
  ASSERT_EQ(layout.strips.size(), 1u);
  EXPECT_GE(layout.strips[0].width, picture.cols / 2);
  EXPECT_GE(layout.strips[0].width, 30 * layout.text_height_px);
  // The caption is all there: it names the length, and what it says is inside the picture.
  std::string all;
  for (const auto& t : layout.texts) all += t.text + " ";
  EXPECT_NE(all.find(fmt::format("length {:.4f} mm", result.metrics.sides[0].length_m * 1e3)), std::string::npos) << all;
  EXPECT_NE(all.find("width"), std::string::npos) << all;
}

// A triangle on a scan 2400 × 2100 px: its sides are numbered next to their middles, text scales up.
TEST(Overlay, TriangleSidesAreNumberedAndTheTextScalesWithThePicture) {
  RenderOptions o = quiet_paper();
  const auto scan = render_scan(sample_shape(triangle_shape(45e-3), {0.05e-3, 8e-3, 30e-3}), true, o);
  ScanOptions so;
  so.sides = 3;
  const auto result = analyse_scan(scan.image, scan.dpi, so);
  OverlayLayout layout;
  const cv::Mat picture = draw_overlay(scan.image, result, &layout);
  expect_readable(picture, layout, scan.dpi);
  EXPECT_GE(layout.text_height_px, 25);  // 15 px text on such a picture was unreadable
  ASSERT_EQ(layout.side_numbers.size(), 3u);
  ASSERT_EQ(layout.strips.size(), 3u);
  const double k = scan.dpi / 0.0254 * layout.scale;
  for (std::size_t i = 0; i < 3; ++i) {
    // The disc is nearer its own side's middle than any other side's.
    const cv::Rect& d = layout.side_numbers[i];
    const Point2 centre{d.x + d.width / 2.0, d.y + d.height / 2.0};
    std::vector<double> dist;
    for (const auto& s : result.metrics.sides) {
      const Point2 mid = (s.start + s.end) / 2 * k + Point2{layout.scan.x, layout.scan.y};
      dist.push_back((mid - centre).norm());
    }
    EXPECT_EQ(std::min_element(dist.begin(), dist.end()) - dist.begin(), static_cast<std::ptrdiff_t>(i)) << "disc " << i + 1;
    EXPECT_GT(count_colour(picture, d, {30, 30, 30}), 5) << "disc " << i + 1 << " has no number";
  }
  for (std::size_t i = 0; i + 1 < layout.strips.size(); ++i) EXPECT_LE(layout.strips[i].y + layout.strips[i].height, layout.strips[i + 1].y);
}

// A scan above 25 Mpx is drawn smaller, and says so; the scale bar follows the scale.
TEST(Overlay, ALargeScanIsDrawnSmallerAndSaysSo) {
  cv::Mat grey(6000, 5000, CV_8U, cv::Scalar(215));
  cv::line(grey, {700, 3000}, {4300, 3040}, cv::Scalar(70), 9, cv::LINE_AA);
  const auto result = analyse_scan(grey, 1200, {});
  OverlayLayout layout;
  const cv::Mat picture = draw_overlay(grey, result, &layout);
  EXPECT_LT(layout.scale, 1.0);
  EXPECT_NEAR(layout.scan.area(), 25e6, 0.01 * 25e6);
  expect_readable(picture, layout, 1200);
  const auto said = std::find_if(layout.legend_entries.begin(), layout.legend_entries.end(),
                                 [](const std::string& e) { return e.find("scan shown at") != std::string::npos; });
  EXPECT_NE(said, layout.legend_entries.end());
}

}  // namespace
}  // namespace stiffpath::vision
