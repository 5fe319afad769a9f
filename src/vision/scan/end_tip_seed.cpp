// The farthest dark pixel of a free end along the side's direction: the start of the tip fit.
#include <algorithm>
#include <vector>

#include "end_tip.hpp"

namespace stiffpath::vision::detail {

std::optional<TipExtreme> farthest_dark_point(const cv::Mat& grey, const CoarseGrid& grid, const TipSearch& s) {
  const cv::Rect box = s.box & cv::Rect(0, 0, grey.cols, grey.rows);
  if (box.empty()) return std::nullopt;
  const auto dark = [&](int x, int y) { return 1.0 - pixel(grey, y, x) / grid.paper_at(x + 0.5, y + 0.5) > s.threshold; };
  const int sx = static_cast<int>(s.seed.x()), sy = static_cast<int>(s.seed.y());
  if (!box.contains(cv::Point(sx, sy)) || !dark(sx, sy)) return std::nullopt;
  // Flood fill (4-connected) from the seed over dark pixels inside the box.
  cv::Mat seen = cv::Mat::zeros(box.size(), CV_8U);
  std::vector<cv::Point> stack{{sx, sy}}, members;
  seen.at<std::uint8_t>(sy - box.y, sx - box.x) = 1;
  while (!stack.empty()) {
    const cv::Point p = stack.back();
    stack.pop_back();
    members.push_back(p);
    for (const cv::Point d : {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
      const cv::Point q = p + d;
      if (!box.contains(q) || seen.at<std::uint8_t>(q.y - box.y, q.x - box.x)) continue;
      seen.at<std::uint8_t>(q.y - box.y, q.x - box.x) = 1;
      if (dark(q.x, q.y)) stack.push_back(q);
    }
  }
  const auto along = [&](const cv::Point& p) { return (Point2{p.x + 0.5, p.y + 0.5}).dot(s.outward); };
  double far = -1e300;
  for (const auto& p : members) far = std::max(far, along(p));
  // Across the side: the darkness-weighted centre of the extreme pixels.
  const Point2 across{-s.outward.y(), s.outward.x()};
  double sw = 0, sa = 0;
  for (const auto& p : members) {
    if (along(p) < far - 1.5) continue;
    const double w = 1.0 - pixel(grey, p.y, p.x) / grid.paper_at(p.x + 0.5, p.y + 0.5);
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
