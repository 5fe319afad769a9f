// The farthest dark pixel of a free end along the side's direction: the start of the tip fit.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "end_tip.hpp"

namespace stiffpath::vision::detail {

namespace {

// The pixels darker than `threshold` connected (4-connected) to `start` inside `box`.
std::vector<cv::Point> flood(const cv::Rect& box, const cv::Point& start, const std::function<double(int, int)>& darkness, double threshold) {
  cv::Mat seen = cv::Mat::zeros(box.size(), CV_8U);
  std::vector<cv::Point> stack{start}, members;
  seen.at<std::uint8_t>(start.y - box.y, start.x - box.x) = 1;
  while (!stack.empty()) {
    const cv::Point p = stack.back();
    stack.pop_back();
    members.push_back(p);
    for (const cv::Point d : {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
      const cv::Point q = p + d;
      if (!box.contains(q) || seen.at<std::uint8_t>(q.y - box.y, q.x - box.x)) continue;
      seen.at<std::uint8_t>(q.y - box.y, q.x - box.x) = 1;
      if (darkness(q.x, q.y) > threshold) stack.push_back(q);
    }
  }
  return members;
}

}  // namespace

std::optional<TipExtreme> farthest_dark_point(const cv::Mat& grey, const CoarseGrid& grid, const TipSearch& s) {
  const cv::Rect box = s.box & cv::Rect(0, 0, grey.cols, grey.rows);
  if (box.empty()) return std::nullopt;
  const std::function<double(int, int)> darkness = [&](int x, int y) { return 1.0 - pixel(grey, y, x) / grid.paper_at(x + 0.5, y + 0.5); };
  // The flood starts at the seed's pixel, or the darkest pixel across the mark from it (a seed at the
  // edge of a thin or faint mark's pixel).
  const Point2 across_u{-s.outward.y(), s.outward.x()};
  cv::Point start(static_cast<int>(s.seed.x()), static_cast<int>(s.seed.y()));
  if (!box.contains(start)) return std::nullopt;
  double best = darkness(start.x, start.y);
  for (double t = -s.seed_reach_px; t <= s.seed_reach_px; t += 0.5) {
    const Point2 p = s.seed + t * across_u;
    const cv::Point q(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y())));
    if (!box.contains(q)) continue;
    if (const double d = darkness(q.x, q.y); d > best) best = d, start = q;
  }
  if (!(best > s.threshold)) return std::nullopt;
  const std::vector<cv::Point> members = flood(box, start, darkness, s.threshold);
  const auto along = [&](const cv::Point& p) { return (Point2{p.x + 0.5, p.y + 0.5}).dot(s.outward); };
  double far = -1e300;
  for (const auto& p : members) far = std::max(far, along(p));
  // Across the side: the darkness-weighted centre of the extreme pixels.
  const Point2 across{-s.outward.y(), s.outward.x()};
  double sw = 0, sa = 0;
  for (const auto& p : members) {
    if (along(p) < far - 1.5) continue;
    const double w = darkness(p.x, p.y);
    sw += w;
    sa += w * (Point2{p.x + 0.5, p.y + 0.5}).dot(across);
  }
  TipExtreme out;
  out.point = s.outward * far + across * (sa / sw);
  // A dark pixel on the box's edge within a few pixels of the extreme: the footprint may be cut by the box.
  for (const auto& p : members) {
    const bool edge = p.x == box.x || p.y == box.y || p.x == box.x + box.width - 1 || p.y == box.y + box.height - 1;
    if (edge && along(p) > far - 3.0) out.at_box_edge = true;
  }
  return out;
}

}  // namespace stiffpath::vision::detail
