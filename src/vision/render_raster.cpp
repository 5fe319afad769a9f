// Area-sampled coverage of a round-capped stroke (all points within r of a polyline), via a grid of segment buckets.
#include <algorithm>
#include <cmath>
#include <vector>

#include "stiffpath/vision/render.hpp"

namespace stiffpath::vision {

namespace {

constexpr int kSub = 4;  // sub-samples per pixel and axis

struct Segment {
  Point2 a, d;   // start and direction·length
  double inv_len2;
};

double distance(const Segment& s, double x, double y) {
  const double px = x - s.a.x(), py = y - s.a.y();
  const double t = s.inv_len2 > 0.0 ? std::clamp((px * s.d.x() + py * s.d.y()) * s.inv_len2, 0.0, 1.0) : 0.0;
  return std::hypot(px - t * s.d.x(), py - t * s.d.y());
}

double nearest(const std::vector<Segment>& segs, const std::vector<int>& list, double x, double y) {
  double best = 1e300;
  for (const int i : list) best = std::min(best, distance(segs[i], x, y));
  return best;
}

}  // namespace

void draw_stroke_coverage(cv::Mat& coverage, const std::vector<Point2>& polyline_px, double radius_px) {
  CV_Assert(coverage.type() == CV_32F);
  if (polyline_px.empty() || !(radius_px > 0.0)) return;
  std::vector<Segment> segs;
  for (std::size_t i = 0; i + 1 < polyline_px.size() || (i == 0 && polyline_px.size() == 1); ++i) {
    const Point2 a = polyline_px[i], b = polyline_px.size() == 1 ? a : polyline_px[i + 1];
    const Point2 d = b - a;
    segs.push_back({a, d, d.squaredNorm() > 0.0 ? 1.0 / d.squaredNorm() : 0.0});
  }
  // Buckets of cell × cell pixels holding every segment that comes within radius + 2 px of the cell.
  const int cell = std::max(4, static_cast<int>(std::ceil(radius_px)));
  const int gx = (coverage.cols + cell - 1) / cell, gy = (coverage.rows + cell - 1) / cell;
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(gx) * gy);
  const double reach = radius_px + 2.0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const Point2 a = segs[i].a, b = segs[i].a + segs[i].d;
    const int x0 = std::max(0, static_cast<int>(std::floor((std::min(a.x(), b.x()) - reach) / cell)));
    const int x1 = std::min(gx - 1, static_cast<int>(std::floor((std::max(a.x(), b.x()) + reach) / cell)));
    const int y0 = std::max(0, static_cast<int>(std::floor((std::min(a.y(), b.y()) - reach) / cell)));
    const int y1 = std::min(gy - 1, static_cast<int>(std::floor((std::max(a.y(), b.y()) + reach) / cell)));
    for (int cy = y0; cy <= y1; ++cy) {
      for (int cx = x0; cx <= x1; ++cx) buckets[static_cast<std::size_t>(cy) * gx + cx].push_back(static_cast<int>(i));
    }
  }
  const double sub = 1.0 / kSub;
  for (int cy = 0; cy < gy; ++cy) {
    for (int cx = 0; cx < gx; ++cx) {
      const auto& list = buckets[static_cast<std::size_t>(cy) * gx + cx];
      if (list.empty()) continue;
      for (int y = cy * cell; y < std::min(coverage.rows, (cy + 1) * cell); ++y) {
        float* row = coverage.ptr<float>(y);
        for (int x = cx * cell; x < std::min(coverage.cols, (cx + 1) * cell); ++x) {
          const double d = nearest(segs, list, x + 0.5, y + 0.5) - radius_px;
          double value;
          if (d > 0.75) continue;
          if (d < -0.75) {
            value = 1.0;
          } else {
            // Area sampling: kSub² sub-pixels, each with a linear ramp one sub-pixel wide across the edge.
            double sum = 0.0;
            for (int sy = 0; sy < kSub; ++sy) {
              for (int sx = 0; sx < kSub; ++sx) {
                const double ds = nearest(segs, list, x + (sx + 0.5) * sub, y + (sy + 0.5) * sub) - radius_px;
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

}  // namespace stiffpath::vision
