// The dark features of the coarse grid, and the one mark among them: specks ignored, two marks or a border contact refused.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

Features find_features(const CoarseGrid& grid) {
  Features out;
  cv::Mat stats, centroids;
  const int count = cv::connectedComponentsWithStats(grid.mask, out.labels, stats, centroids, 8, CV_32S);
  out.list.resize(static_cast<std::size_t>(std::max(count - 1, 0)));
  for (int y = 0; y < out.labels.rows; ++y) {
    const int* lab = out.labels.ptr<int>(y);
    const float* dark = grid.darkness.ptr<float>(y);
    for (int x = 0; x < out.labels.cols; ++x) {
      if (lab[x] > 0) out.list[static_cast<std::size_t>(lab[x] - 1)].mass += dark[x];
    }
  }
  const int gw = grid.mask.cols, gh = grid.mask.rows;
  for (int i = 1; i < count; ++i) {
    Feature& f = out.list[static_cast<std::size_t>(i - 1)];
    f.label = i;
    f.box = cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP), stats.at<int>(i, cv::CC_STAT_WIDTH),
                     stats.at<int>(i, cv::CC_STAT_HEIGHT));
    f.extent_px = std::hypot(f.box.width, f.box.height) * grid.cell;
    const cv::Rect& b = f.box;
    if (b.x == 0) f.border = "left";
    else if (b.y == 0) f.border = "top";
    else if (b.x + b.width == gw) f.border = "right";
    else if (b.y + b.height == gh) f.border = "bottom";
  }
  return out;
}

MarkComponent mark_of(const CoarseGrid& grid, const Features& features, const Feature& f, const ScanTuning& tuning) {
  MarkComponent mark;
  mark.label = f.label;
  mark.box = f.box;
  std::vector<double> dark;
  for (int y = f.box.y; y < f.box.y + f.box.height; ++y) {
    const int* lab = features.labels.ptr<int>(y);
    for (int x = f.box.x; x < f.box.x + f.box.width; ++x) {
      if (lab[x] != f.label) continue;
      const double d = grid.darkness.at<float>(y, x);
      mark.cells_px.emplace_back((x + 0.5) * grid.cell, (y + 0.5) * grid.cell);
      mark.weights.push_back(d);
      dark.push_back(d);
    }
  }
  std::sort(dark.begin(), dark.end());
  mark.full_darkness = dark[static_cast<std::size_t>(tuning.full_darkness_quantile * static_cast<double>(dark.size() - 1))];
  double area = 0.0;
  for (const double d : dark) area += std::min(1.0, d / mark.full_darkness);
  area *= grid.cell * grid.cell;
  const cv::Mat one = (features.labels(f.box) == f.label);
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(one, contours, cv::RETR_LIST, cv::CHAIN_APPROX_NONE);
  double perimeter = 0.0;
  for (const auto& c : contours) perimeter += cv::arcLength(c, true);
  mark.width_px = std::max(1.0, area / std::max(1.0, perimeter * grid.cell / 2));
  return mark;
}

MarkComponent find_mark(const CoarseGrid& grid, double px_per_m, const ScanOptions& options) {
  const SourceLocation where{options.label, 0, 0};
  Features features = find_features(grid);
  // Features that are not marks (the paper's edge on the lid, smudges) are set aside first, with a warning.
  const cv::Mat paper = paper_cells(grid);
  std::vector<const Feature*> order;
  std::vector<std::string> warnings;
  for (const auto& f : features.list) {
    if (f.extent_px >= options.min_mark_length_m * px_per_m) {
      if (const std::string artefact = paper_artefact(grid, features, f, paper, px_per_m, options.tuning); !artefact.empty()) {
        const Point2 at{(f.box.x + f.box.width / 2.0) * grid.cell, (f.box.y + f.box.height / 2.0) * grid.cell};
        warnings.push_back(fmt::format("ignored a dark feature {:.2f} mm across near {}: {}", f.extent_px / px_per_m * 1e3,
                                       position_text(at, px_per_m, options), artefact));
        continue;
      }
    }
    order.push_back(&f);
  }
  std::sort(order.begin(), order.end(), [](const Feature* a, const Feature* b) { return a->mass > b->mass; });
  const double min_px = options.min_mark_length_m * px_per_m;
  const auto to_mm = [&](double px) { return px / px_per_m * 1e3; };
  if (order.empty() || order.front()->extent_px < min_px) {
    std::string why = order.empty() ? std::string("no feature is darker than the paper's noise")
                                    : fmt::format("the largest dark feature is only {:.2f} mm across", to_mm(order.front()->extent_px));
    for (const auto& w : warnings) why += "; " + w;
    throw Error(where, "no mark found: " + why);
  }
  const Feature& main = *order.front();
  int specks = 0;
  for (std::size_t i = 1; i < order.size(); ++i) {
    const Feature& f = *order[i];
    const Point2 at{(f.box.x + f.box.width / 2.0) * grid.cell, (f.box.y + f.box.height / 2.0) * grid.cell};
    if (f.extent_px >= options.tuning.second_mark_ratio * main.extent_px && f.extent_px >= min_px) {
      throw Error(where, fmt::format("found two separate marks ({:.2f} mm and {:.2f} mm across, the second near {}): the scan "
                                     "must show one marked path, or the mark is interrupted; pass --roi to pick one, or "
                                     "--all-marks to measure each", to_mm(main.extent_px), to_mm(f.extent_px),
                                     position_text(at, px_per_m, options)));
    }
    if (f.extent_px >= min_px) {
      warnings.push_back(fmt::format("ignored a separate dark feature {:.2f} mm across near {}", to_mm(f.extent_px),
                                     position_text(at, px_per_m, options)));
    } else {
      ++specks;
    }
  }
  if (!main.border.empty()) {
    throw Error(where, fmt::format("the mark touches the {} border of the {}: it may be cut off, so it cannot be measured; {}",
                                   main.border, options.roi_px.empty() ? "image" : "region (--roi)",
                                   options.roi_px.empty() ? "scan it with paper around it" : "widen the region"));
  }
  MarkComponent mark = mark_of(grid, features, main, options.tuning);
  mark.specks = specks;
  mark.warnings = std::move(warnings);
  return mark;
}

}  // namespace stiffpath::vision::detail
