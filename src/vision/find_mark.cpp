// Finding the mark among the dark features of the coarse grid: specks ignored, two marks or a border contact refused.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

namespace {

struct Feature {
  int label = 0;
  double mass = 0;       // Σ darkness of its cells
  double extent_px = 0;  // bounding-box diagonal
  cv::Rect box;          // in cells
};

}  // namespace

MarkComponent find_mark(const CoarseGrid& grid, double px_per_m, const ScanOptions& options) {
  const SourceLocation where{options.label, 0, 0};
  MarkComponent mark;
  cv::Mat stats, centroids;
  const int count = cv::connectedComponentsWithStats(grid.mask, mark.labels, stats, centroids, 8, CV_32S);
  std::vector<Feature> features(static_cast<std::size_t>(std::max(count, 1)));
  for (int y = 0; y < mark.labels.rows; ++y) {
    const int* lab = mark.labels.ptr<int>(y);
    const float* dark = grid.darkness.ptr<float>(y);
    for (int x = 0; x < mark.labels.cols; ++x) {
      if (lab[x] > 0) features[static_cast<std::size_t>(lab[x])].mass += dark[x];
    }
  }
  for (int i = 1; i < count; ++i) {
    auto& f = features[static_cast<std::size_t>(i)];
    f.label = i;
    f.box = cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                     stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    f.extent_px = std::hypot(f.box.width, f.box.height) * grid.cell;
  }
  features.erase(features.begin());
  std::sort(features.begin(), features.end(), [](const Feature& a, const Feature& b) { return a.mass > b.mass; });
  const double min_px = options.min_mark_length_m * px_per_m;
  const auto to_mm = [&](double px) { return px / px_per_m * 1e3; };
  if (features.empty() || features.front().extent_px < min_px) {
    throw Error(where, fmt::format("no mark found: {}", features.empty()
                                       ? std::string("no feature is darker than the paper's noise")
                                       : fmt::format("the largest dark feature is only {:.2f} mm across", to_mm(features.front().extent_px))));
  }
  const Feature& main = features.front();
  for (std::size_t i = 1; i < features.size(); ++i) {
    const Feature& f = features[i];
    const cv::Point2d at((f.box.x + f.box.width / 2.0) * grid.cell, (f.box.y + f.box.height / 2.0) * grid.cell);
    if (f.extent_px >= 0.2 * main.extent_px && f.extent_px >= min_px) {
      throw Error(where, fmt::format("found two separate marks ({:.2f} mm and {:.2f} mm across, the second near x = {:.2f} mm, "
                                     "y = {:.2f} mm): the scan must show one marked path, or the mark is interrupted",
                                     to_mm(main.extent_px), to_mm(f.extent_px), to_mm(at.x), to_mm(at.y)));
    }
    if (f.extent_px >= min_px) {
      mark.warnings.push_back(fmt::format("ignored a separate dark feature {:.2f} mm across near x = {:.2f} mm, y = {:.2f} mm",
                                          to_mm(f.extent_px), to_mm(at.x), to_mm(at.y)));
    } else {
      ++mark.specks;
    }
  }
  const cv::Rect& b = main.box;
  const int gw = grid.mask.cols, gh = grid.mask.rows;
  if (b.x == 0 || b.y == 0 || b.x + b.width == gw || b.y + b.height == gh) {
    const char* edge = b.x == 0 ? "left" : b.y == 0 ? "top" : b.x + b.width == gw ? "right" : "bottom";
    throw Error(where, fmt::format("the mark touches the {} border of the image: it may be cut off, so it cannot be "
                                   "measured; scan it with paper around it", edge));
  }

  mark.label = main.label;
  mark.box = b;
  std::vector<double> dark;
  for (int y = b.y; y < b.y + b.height; ++y) {
    const int* lab = mark.labels.ptr<int>(y);
    for (int x = b.x; x < b.x + b.width; ++x) {
      if (lab[x] != mark.label) continue;
      const double d = grid.darkness.at<float>(y, x);
      mark.cells_px.emplace_back((x + 0.5) * grid.cell, (y + 0.5) * grid.cell);
      mark.weights.push_back(d);
      dark.push_back(d);
    }
  }
  std::sort(dark.begin(), dark.end());
  mark.full_darkness = dark[static_cast<std::size_t>(0.9 * static_cast<double>(dark.size() - 1))];
  double area = 0.0;
  for (const double d : dark) area += std::min(1.0, d / mark.full_darkness);
  area *= grid.cell * grid.cell;
  cv::Mat one = (mark.labels(b) == mark.label);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(one, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  double perimeter = 0.0;
  for (const auto& c : contours) perimeter += cv::arcLength(c, true);
  mark.width_px = std::max(1.0, area / std::max(1.0, perimeter * grid.cell / 2));
  return mark;
}

}  // namespace stiffpath::vision::detail
