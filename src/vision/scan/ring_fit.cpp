// A ring's centre line from darkness centroids along rays, and the circle through it (algebraic fit, then geometric).
#include "ring_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

namespace {

constexpr int kRays = 720;           // one centre-line point per half degree
constexpr double kStepPx = 0.25;     // sampling step along a ray
constexpr double kBlurMarginPx = 3;  // the centroid's window: the ring's width + this on each side

// Least-squares circle through the points: the algebraic fit x² + y² + Dx + Ey + F = 0, then Gauss–Newton
// on the geometric distances |p − c| − r (the algebraic fit is biased when the points cover an arc only).
bool fit_circle(const std::vector<Point2>& pts, Point2& centre, double& radius) {
  if (pts.size() < 8) return false;
  Eigen::MatrixXd a(pts.size(), 3);
  Eigen::VectorXd b(pts.size());
  const Point2 mean = [&] {
    Point2 m{0, 0};
    for (const auto& p : pts) m += p;
    return Point2(m / static_cast<double>(pts.size()));
  }();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point2 p = pts[i] - mean;
    a(static_cast<Eigen::Index>(i), 0) = p.x();
    a(static_cast<Eigen::Index>(i), 1) = p.y();
    a(static_cast<Eigen::Index>(i), 2) = 1.0;
    b(static_cast<Eigen::Index>(i)) = -p.squaredNorm();
  }
  const Eigen::Vector3d s = a.colPivHouseholderQr().solve(b);
  Point2 c{-s(0) / 2, -s(1) / 2};
  double r2 = c.squaredNorm() - s(2);
  if (!(r2 > 0) || !c.allFinite()) return false;
  double r = std::sqrt(r2);
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (const auto& q : pts) {
      const Point2 d = q - mean - c;
      const double dist = std::max(d.norm(), 1e-12);
      const Eigen::Vector3d j(-d.x() / dist, -d.y() / dist, -1.0);
      jtj += j * j.transpose();
      jtr += j * (dist - r);
    }
    const Eigen::Vector3d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) return false;
    c += Point2{step(0), step(1)};
    r += step(2);
    if (step.norm() < 1e-9) break;
  }
  centre = c + mean;
  radius = r;
  return radius > 0 && centre.allFinite();
}

}  // namespace

double darkness_at(const cv::Mat& grey, const CoarseGrid& grid, const Point2& p) {
  const double u = p.x() - 0.5, v = p.y() - 0.5;
  const int x0 = static_cast<int>(std::floor(u)), y0 = static_cast<int>(std::floor(v));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= grey.cols || y0 + 1 >= grey.rows) return 0.0;
  const double fx = u - x0, fy = v - y0;
  const double value = (1 - fy) * ((1 - fx) * pixel(grey, y0, x0) + fx * pixel(grey, y0, x0 + 1)) +
                       fy * ((1 - fx) * pixel(grey, y0 + 1, x0) + fx * pixel(grey, y0 + 1, x0 + 1));
  return 1.0 - value / grid.paper_at(p.x(), p.y());
}

RingFit fit_ring(const cv::Mat& grey, const CoarseGrid& grid, Point2 centre, double radius_px, double radius_slack_px) {
  RingFit fit;
  double r_lo = std::max(1.0, radius_px - radius_slack_px), r_hi = radius_px + radius_slack_px;
  for (int pass = 0; pass < 3; ++pass) {
    // The mean radial profile over all rays: where the ring is and how wide.
    const int n = static_cast<int>(std::ceil((r_hi - r_lo) / kStepPx)) + 1;
    std::vector<double> profile(static_cast<std::size_t>(n), 0.0);
    for (int k = 0; k < kRays; ++k) {
      const double a = 2 * std::numbers::pi * k / kRays;
      const Point2 u{std::cos(a), std::sin(a)};
      for (int i = 0; i < n; ++i) profile[static_cast<std::size_t>(i)] += darkness_at(grey, grid, centre + (r_lo + i * kStepPx) * u) / kRays;
    }
    const auto peak = std::max_element(profile.begin(), profile.end());
    if (!(*peak > 0.02)) return fit;
    double mass = 0, moment = 0;
    for (int i = 0; i < n; ++i) {
      const double d = profile[static_cast<std::size_t>(i)];
      if (d < 0.5 * *peak) continue;
      mass += d, moment += d * (r_lo + i * kStepPx);
    }
    const double ring_r = moment / mass;
    double integral = 0;
    for (const double d : profile) integral += std::max(0.0, d) * kStepPx;
    fit.width = integral / *peak;
    // Each ray's centroid over the ring's width and the blur.
    const double half = fit.width / 2 + kBlurMarginPx;
    std::vector<Point2> pts;
    std::vector<double> peaks;
    int crossed = 0;
    for (int k = 0; k < kRays; ++k) {
      const double a = 2 * std::numbers::pi * k / kRays;
      const Point2 u{std::cos(a), std::sin(a)};
      double m = 0, mr = 0, top = 0;
      for (double r = ring_r - half; r <= ring_r + half; r += kStepPx) {
        const double d = darkness_at(grey, grid, centre + r * u);
        m += d, mr += d * r, top = std::max(top, d);
      }
      if (!(top > 0.5 * *peak) || !(m > 0)) continue;  // no ring on this ray: a gap
      ++crossed;
      peaks.push_back(top);
      pts.push_back(centre + (mr / m) * u);
    }
    fit.covered = static_cast<double>(crossed) / kRays;
    fit.darkness = core::median(peaks, core::MedianRule::upper_middle);
    Point2 c;
    double r;
    if (!fit_circle(pts, c, r)) return fit;
    double sq = 0;
    for (const auto& p : pts) sq += std::pow((p - c).norm() - r, 2);
    fit.centre = c;
    fit.radius = r;
    fit.rms = std::sqrt(sq / static_cast<double>(pts.size()));
    fit.points = pts.size();
    fit.ok = true;
    // Recentred, the next pass looks in a narrower band about the ring.
    centre = c;
    r_lo = std::max(1.0, r - fit.width - 2 * kBlurMarginPx);
    r_hi = r + fit.width + 2 * kBlurMarginPx;
  }
  return fit;
}

}  // namespace stiffpath::vision::detail
