// Dark features that are not laser marks: the paper's edge on the scanner's lid (a brightness step) and smudges (too wide).
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "scan_internal.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

// The grey level of a cell (its block mean), from its darkness and the paper level there.
double cell_level(const CoarseGrid& grid, int x, int y) {
  return grid.paper_at((x + 0.5) * grid.cell, (y + 0.5) * grid.cell) * (1.0 - grid.darkness.at<float>(y, x));
}

}  // namespace

cv::Mat paper_cells(const CoarseGrid& grid) {
  cv::Mat dark;
  cv::dilate(grid.mask, dark, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(3, 3)));
  return dark == 0;
}

std::string paper_artefact(const CoarseGrid& grid, const Features& features, const Feature& f, const cv::Mat& paper, double px_per_m,
                           const ScanTuning& tuning) {
  // A mark lies on paper: the paper just beyond it is as bright on one side as on the other. The paper's edge
  // separates the paper from the scanner's lid: beyond its shadow (and the band the block levels lag over) the
  // two sides differ by the step. At each cell, along each axis whose probes both reach paper, the relative
  // difference of the first paper cells on the two sides; the feature's median of the larger one is its step.
  const int reach = tuning.edge_reach_cells;
  const auto probe = [&](int x, int y, int dx, int dy) -> std::optional<double> {
    for (int k = 1; k <= reach; ++k) {
      const int px = x + k * dx, py = y + k * dy;
      if (px < 0 || py < 0 || px >= paper.cols || py >= paper.rows) return std::nullopt;
      if (paper.at<std::uint8_t>(py, px) != 0) return cell_level(grid, px, py);
    }
    return std::nullopt;
  };
  std::vector<double> steps;
  const int stride = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(f.box.area()) / 4e4)));  // at most ~40 000 cells looked at
  for (int y = f.box.y; y < f.box.y + f.box.height; y += stride) {
    const int* label = features.labels.ptr<int>(y);
    for (int x = f.box.x; x < f.box.x + f.box.width; x += stride) {
      if (label[x] != f.label) continue;
      double step = -1;
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
        const auto a = probe(x, y, dx, dy), b = probe(x, y, -dx, -dy);
        if (a && b && *a + *b > 0) step = std::max(step, 2 * std::abs(*a - *b) / (*a + *b));
      }
      if (step >= 0) steps.push_back(step);
    }
  }
  const auto mm = [&](double px) { return px / px_per_m * 1e3; };
  const double step = core::median(steps, core::MedianRule::upper_middle);
  const double noise = tuning.dark_noise_sigmas * grid.sigma;
  if (!steps.empty() && step > std::max(noise, tuning.edge_step)) {
    return fmt::format("the edge of the paper: the paper's brightness steps by {:.1f} % across it (a mark has paper alike on both sides)",
                       100 * step);
  }
  const MarkComponent shape = mark_of(grid, features, f, tuning);
  if (shape.width_px > tuning.max_mark_width_m * px_per_m) {
    return fmt::format("a smudge or a shadow, not a laser mark: {:.2f} mm wide, wider than the {:.2f} mm of any laser mark", mm(shape.width_px),
                       tuning.max_mark_width_m * 1e3);
  }
  return {};
}

}  // namespace stiffpath::vision::detail
