// Area-sampled coverage of round-capped strokes (all points within r of a polyline), band by band with per-band segment buckets.
#include <algorithm>
#include <cmath>
#include <vector>

#include "render_internal.hpp"

namespace stiffpath::vision {

namespace detail {

namespace {

constexpr int kSub = 4;  // sub-samples per pixel and axis

}  // namespace

StrokeRaster::StrokeRaster(const std::vector<std::vector<Point2>>& polylines_px, double radius_px) : radius_(radius_px) {
  for (const auto& polyline : polylines_px) {
    for (std::size_t i = 0; i + 1 < polyline.size() || (i == 0 && polyline.size() == 1); ++i) {
      const Point2 a = polyline[i], b = polyline.size() == 1 ? a : polyline[i + 1];
      const Point2 d = b - a;
      segments_.push_back({a, d, d.squaredNorm() > 0.0 ? 1.0 / d.squaredNorm() : 0.0});
      rows_.emplace_back(std::min(a.y(), b.y()) - radius_px - 2.0, std::max(a.y(), b.y()) + radius_px + 2.0);
    }
  }
}

void StrokeRaster::draw(cv::Mat& coverage, int row0) const {
  CV_Assert(coverage.type() == CV_32F);
  if (segments_.empty() || !(radius_ > 0.0)) return;
  const double r = radius_;
  // Buckets of cell × cell pixels of this band, each holding every segment that comes within r + 2 px.
  const int cell = std::max(4, static_cast<int>(std::ceil(r)));
  const int gx = (coverage.cols + cell - 1) / cell, gy = (coverage.rows + cell - 1) / cell;
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(gx) * gy);
  const double reach = r + 2.0, band_lo = row0, band_hi = row0 + coverage.rows;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    if (rows_[i].second < band_lo || rows_[i].first > band_hi) continue;
    const Point2 a = segments_[i].a, b = segments_[i].a + segments_[i].d;
    const int x0 = std::max(0, static_cast<int>(std::floor((std::min(a.x(), b.x()) - reach) / cell)));
    const int x1 = std::min(gx - 1, static_cast<int>(std::floor((std::max(a.x(), b.x()) + reach) / cell)));
    const int y0 = std::max(0, static_cast<int>(std::floor((std::min(a.y(), b.y()) - reach - row0) / cell)));
    const int y1 = std::min(gy - 1, static_cast<int>(std::floor((std::max(a.y(), b.y()) + reach - row0) / cell)));
    for (int cy = y0; cy <= y1; ++cy) {
      for (int cx = x0; cx <= x1; ++cx) buckets[static_cast<std::size_t>(cy) * gx + cx].push_back(static_cast<int>(i));
    }
  }
  const auto nearest = [&](const std::vector<int>& list, double x, double y) {
    double best = 1e300;
    for (const int i : list) {
      const Segment& s = segments_[static_cast<std::size_t>(i)];
      const double px = x - s.a.x(), py = y - s.a.y();
      const double t = s.inv_len2 > 0.0 ? std::clamp((px * s.d.x() + py * s.d.y()) * s.inv_len2, 0.0, 1.0) : 0.0;
      best = std::min(best, std::hypot(px - t * s.d.x(), py - t * s.d.y()));
    }
    return best;
  };
  const double sub = 1.0 / kSub;
  for (int cy = 0; cy < gy; ++cy) {
    for (int cx = 0; cx < gx; ++cx) {
      const auto& list = buckets[static_cast<std::size_t>(cy) * gx + cx];
      if (list.empty()) continue;
      for (int y = cy * cell; y < std::min(coverage.rows, (cy + 1) * cell); ++y) {
        float* row = coverage.ptr<float>(y);
        const double iy = y + row0;
        for (int x = cx * cell; x < std::min(coverage.cols, (cx + 1) * cell); ++x) {
          const double d = nearest(list, x + 0.5, iy + 0.5) - r;
          double value;
          if (d > 0.75) continue;
          if (d < -0.75) {
            value = 1.0;
          } else {
            // Area sampling: kSub² sub-pixels, each with a linear ramp one sub-pixel wide across the edge.
            double sum = 0.0;
            for (int sy = 0; sy < kSub; ++sy) {
              for (int sx = 0; sx < kSub; ++sx) {
                const double ds = nearest(list, x + (sx + 0.5) * sub, iy + (sy + 0.5) * sub) - r;
                sum += std::clamp(0.5 - ds / sub, 0.0, 1.0);
              }
            }
            value = sum / (kSub * kSub);
          }
          row[x] = std::max(row[x], static_cast<float>(value));
        }
      }
    }
  }
}

}  // namespace detail

void draw_stroke_coverage(cv::Mat& coverage, const std::vector<Point2>& polyline_px, double radius_px) {
  CV_Assert(coverage.type() == CV_32F);
  if (polyline_px.empty()) return;
  detail::StrokeRaster({polyline_px}, radius_px).draw(coverage, 0);
}

}  // namespace stiffpath::vision
