// Gauss–Newton fit of a blurred round spot to the outermost edge of a free end of the mark.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "blurred_disk.hpp"
#include "end_tip.hpp"

namespace stiffpath::vision::detail {

namespace {

// The Gauss–Newton fit's numerical settings (not tuning of the method: they only make the fit converge).
struct FitSettings {
  int iterations = 16;              // most iterations
  int window_iterations = 6;        // the pixel window follows the circle for the first iterations, then stays
  double window_sigmas = 3.0;       // the window: within this many σ (+ window_px) of the circle
  double window_px = 1.0;
  std::size_t min_pixels = 8;       // fewer pixels: no fit
  double derivative_step_px = 1e-3; // finite-difference step of the blurred disk's derivatives
  double early_damping = 1e-3;      // Levenberg damping of the first (window) iterations, then late_damping
  double late_damping = 1e-9;
  double min_step_limit_px = 1.0;   // the centre moves at most max(this, step_limit_radii·R) per iteration
  double step_limit_radii = 0.5;
  double min_radius_ratio = 0.25, max_radius_ratio = 6.0;  // R stays within these multiples of the guess
  double stop_move_px = 1e-5;       // converged: a step this small after the window iterations
  double converged_move_px = 1e-3;  // the last step must be below this to call the fit converged
};
constexpr FitSettings kFit{};

struct Sample {
  Point2 at;        // pixel centre (image px)
  double darkness;  // 1 − I/paper
};

// Pixels within half_angle of `outward` seen from c and within 3σ + 1 px of the circle (c, R).
std::vector<Sample> window(const cv::Mat& grey, const CoarseGrid& grid, const TipGuess& g, const Point2& c, double radius) {
  const double inner = std::max(0.0, radius - kFit.window_sigmas * g.sigma - kFit.window_px);
  const double outer = radius + kFit.window_sigmas * g.sigma + kFit.window_px;
  const double cos_max = std::cos(g.half_angle_rad);
  const int x0 = std::max(0, static_cast<int>(std::floor(c.x() - outer))), x1 = std::min(grey.cols - 1, static_cast<int>(std::ceil(c.x() + outer)));
  const int y0 = std::max(0, static_cast<int>(std::floor(c.y() - outer))), y1 = std::min(grey.rows - 1, static_cast<int>(std::ceil(c.y() + outer)));
  std::vector<Sample> out;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Point2 p{x + 0.5, y + 0.5};
      const Point2 rel = p - c;
      const double rho = rel.norm();
      if (rho < inner || rho > outer || rel.dot(g.outward) < cos_max * rho) continue;
      out.push_back({p, 1.0 - pixel(grey, y, x) / grid.paper_at(p.x(), p.y())});
    }
  }
  return out;
}

}  // namespace

TipFit fit_end_tip(const cv::Mat& grey, const CoarseGrid& grid, const TipGuess& g) {
  // Parameters: offset a (paper level off the coarse grid's), scale b (= k), centre c, radius R.
  TipFit fit;  // a failed fit (too few pixels, a singular system) reports the guess, not converged
  fit.centre = g.centre;
  fit.radius = g.radius;
  fit.darkness = g.darkness;
  fit.rms = 1e9;
  double a = 0, b = g.darkness, radius = g.radius;
  Point2 c = g.centre;
  std::vector<Sample> samples;
  const double h = kFit.derivative_step_px;
  double last_move = 1e300;
  for (int it = 0; it < kFit.iterations; ++it) {
    const bool following = it < kFit.window_iterations;
    if (following) samples = window(grey, grid, g, c, radius);
    if (samples.size() < kFit.min_pixels) return fit;
    Eigen::Matrix<double, 5, 5> normal = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> rhs = Eigen::Matrix<double, 5, 1>::Zero();
    for (const auto& s : samples) {
      const Point2 rel = s.at - c;
      const double rho = std::max(rel.norm(), 1e-9);
      const double value = blurred_disk(rho, radius, g.sigma);
      const double d_rho = (blurred_disk(rho + h, radius, g.sigma) - value) / h;
      const double d_r = (blurred_disk(rho, radius + h, g.sigma) - value) / h;
      Eigen::Matrix<double, 5, 1> j;
      j << 1.0, value, -b * d_rho * rel.x() / rho, -b * d_rho * rel.y() / rho, b * d_r;
      normal += j * j.transpose();
      rhs += j * (s.darkness - a - b * value);
    }
    // A little damping keeps the first steps (from a guess up to a pixel off) inside the basin.
    normal.diagonal() *= 1.0 + (following ? kFit.early_damping : kFit.late_damping);
    const Eigen::Matrix<double, 5, 1> step = normal.ldlt().solve(rhs);
    if (!step.allFinite()) return fit;
    const double move = std::hypot(step(2), step(3));
    const double limit = std::max(kFit.min_step_limit_px, kFit.step_limit_radii * radius);  // px per iteration
    const double scale = move > limit ? limit / move : 1.0;
    a += scale * step(0);
    b += scale * step(1);
    c += scale * Point2{step(2), step(3)};
    radius = std::clamp(radius + scale * step(4), kFit.min_radius_ratio * g.radius, kFit.max_radius_ratio * g.radius);
    last_move = std::max(move, std::abs(step(4)));
    if (!following && last_move < kFit.stop_move_px) break;
  }
  double sq = 0;
  for (const auto& s : samples) sq += std::pow(s.darkness - a - b * blurred_disk((s.at - c).norm(), radius, g.sigma), 2);
  fit.centre = c;
  fit.radius = radius;
  fit.darkness = b;
  fit.pixels = samples.size();
  fit.rms = b > 0 ? std::sqrt(sq / static_cast<double>(samples.size())) / b : 1e9;
  fit.converged = last_move < kFit.converged_move_px && b > 0;  // a square cut keeps jumping between its corners
  return fit;
}

}  // namespace stiffpath::vision::detail
