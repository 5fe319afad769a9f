// Coarse grid of a scan: block means, paper level from block medians (shading), darkness and its noise threshold.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "scan_internal.hpp"
#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

template <class T>
void block_means(const cv::Mat& grey, int cell, cv::Mat& mean) {
  const int gh = mean.rows, gw = mean.cols;
  std::vector<double> sums(static_cast<std::size_t>(gw));
  std::vector<int> counts(static_cast<std::size_t>(gw));
  for (int gy = 0; gy < gh; ++gy) {
    std::fill(sums.begin(), sums.end(), 0.0);
    std::fill(counts.begin(), counts.end(), 0);
    for (int y = gy * cell; y < std::min(grey.rows, (gy + 1) * cell); ++y) {
      const T* row = grey.ptr<T>(y);
      for (int gx = 0; gx < gw; ++gx) {
        const int x0 = gx * cell, x1 = std::min(grey.cols, x0 + cell);
        unsigned long acc = 0;
        for (int x = x0; x < x1; ++x) acc += row[x];
        sums[static_cast<std::size_t>(gx)] += static_cast<double>(acc);
        counts[static_cast<std::size_t>(gx)] += x1 - x0;
      }
    }
    float* out = mean.ptr<float>(gy);
    for (int gx = 0; gx < gw; ++gx) out[gx] = static_cast<float>(sums[static_cast<std::size_t>(gx)] / counts[static_cast<std::size_t>(gx)]);
  }
}

// Paper levels and noise from hundreds to a million cells: the upper middle, in place (no copy of a large sample).
double median_of(std::vector<float>& v) { return core::median_in_place(std::span<float>(v), core::MedianRule::upper_middle); }

}  // namespace

double CoarseGrid::paper_at(double x_px, double y_px) const {
  // Block centres sit at (b + 0.5)·block_cells cells.
  const double block_px = static_cast<double>(block_cells) * cell;
  const double bx = std::clamp(x_px / block_px - 0.5, 0.0, blocks.cols - 1.0);
  const double by = std::clamp(y_px / block_px - 0.5, 0.0, blocks.rows - 1.0);
  const int x0 = static_cast<int>(bx), y0 = static_cast<int>(by);
  const int x1 = std::min(x0 + 1, blocks.cols - 1), y1 = std::min(y0 + 1, blocks.rows - 1);
  const double fx = bx - x0, fy = by - y0;
  const auto at = [&](int y, int x) { return static_cast<double>(blocks.at<float>(y, x)); };
  return (1 - fy) * ((1 - fx) * at(y0, x0) + fx * at(y0, x1)) + fy * ((1 - fx) * at(y1, x0) + fx * at(y1, x1));
}

CoarseGrid build_coarse_grid(const cv::Mat& grey, const ScanTuning& tuning) {
  CoarseGrid grid;
  const int cell = tuning.cell_px;
  grid.cell = cell;
  grid.block_cells = tuning.paper_block_cells;
  const int gh = (grey.rows + cell - 1) / cell, gw = (grey.cols + cell - 1) / cell;
  // The block means are made in the darkness grid and turned into darkness in place (one grid, not two).
  grid.darkness.create(gh, gw, CV_32F);
  const cv::Mat& mean = grid.darkness;
  if (grey.depth() == CV_8U) {
    block_means<std::uint8_t>(grey, cell, grid.darkness);
  } else {
    block_means<std::uint16_t>(grey, cell, grid.darkness);
  }
  // Paper level: median of blocks of cells (16 × 16 cells, 64 px, by default), smoothly interpolated. A
  // mark crossing a block covers a minority of its cells, so the median sees paper; shading is slow.
  const int block = grid.block_cells;
  const int bh = (gh + block - 1) / block, bw = (gw + block - 1) / block;
  cv::Mat& blocks = grid.blocks;
  blocks.create(bh, bw, CV_32F);
  std::vector<float> values;
  for (int by = 0; by < bh; ++by) {
    for (int bx = 0; bx < bw; ++bx) {
      values.clear();
      for (int y = by * block; y < std::min(gh, (by + 1) * block); ++y) {
        for (int x = bx * block; x < std::min(gw, (bx + 1) * block); ++x) values.push_back(mean.at<float>(y, x));
      }
      blocks.at<float>(by, bx) = static_cast<float>(median_of(values));
    }
  }
  for (int y = 0; y < gh; ++y) {
    for (int x = 0; x < gw; ++x) {
      const float bg = std::max(static_cast<float>(grid.paper_at((x + 0.5) * cell, (y + 0.5) * cell)), 1e-3f);
      grid.darkness.at<float>(y, x) = 1.0f - grid.darkness.at<float>(y, x) / bg;
    }
  }
  // The paper's darkness level and noise from every cell, or from an even sample of a million cells on a
  // large scan (the same statistics, without a copy of the whole grid).
  const std::size_t cells = static_cast<std::size_t>(gh) * gw,
                    stride = std::max<std::size_t>(1, cells / std::max<std::size_t>(1, tuning.paper_sample_cells));
  std::vector<float> all;
  all.reserve(cells / stride + 1);
  for (std::size_t i = 0; i < cells; i += stride) all.push_back(grid.darkness.at<float>(static_cast<int>(i / gw), static_cast<int>(i % gw)));
  grid.median = median_of(all);
  for (auto& v : all) v = std::abs(v - static_cast<float>(grid.median));
  grid.sigma = core::kMadToSigma * median_of(all);
  // A cell is dark when it stands 6 σ above the paper's variation, and at least 4 % darker (by default).
  grid.threshold = grid.median + std::max(tuning.dark_noise_sigmas * grid.sigma, tuning.dark_min_darkness);
  cv::compare(grid.darkness, grid.threshold, grid.mask, cv::CMP_GT);
  grid.mask /= 255;
  return grid;
}

}  // namespace stiffpath::vision::detail
