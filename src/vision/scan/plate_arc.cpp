// A plate arc's centre line from its scan: the ink's centre along radial profiles, every 0.1 mm of the commanded circle.
#include "plate_arc.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace stiffpath::vision::detail {

namespace {

constexpr double kStep_m = 0.1e-3;       // between profiles, along the arc
constexpr double kSample_px = 0.25;      // between samples, across it
constexpr double kInkHalf_m = 0.3e-3;    // the centroid's reach about the darkest sample (a mark is ~0.2 mm wide)

// Grey value at the continuous scan position (x, y) in px (pixel centres at +0.5), bilinear; NaN outside the image.
double sample(const cv::Mat& grey, double x, double y) {
  const double u = x - 0.5, v = y - 0.5;
  const int i = static_cast<int>(std::floor(u)), j = static_cast<int>(std::floor(v));
  if (i < 0 || j < 0 || i + 1 >= grey.cols || j + 1 >= grey.rows) return std::nan("");
  const double fu = u - i, fv = v - j;
  const auto at = [&](int r, int c) {
    return grey.depth() == CV_16U ? static_cast<double>(grey.at<std::uint16_t>(r, c)) : static_cast<double>(grey.at<std::uint8_t>(r, c));
  };
  return (1 - fv) * ((1 - fu) * at(j, i) + fu * at(j, i + 1)) + fv * ((1 - fu) * at(j + 1, i) + fu * at(j + 1, i + 1));
}

}  // namespace

std::vector<Eigen::Vector2d> measure_arc(const calibration::StrokeMark& arc, const cv::Mat& grey, double dpi,
                                         const PlateRegistration& registration, double half_width_m, double trim_m,
                                         std::string& why) {
  using Vec2 = Eigen::Vector2d;
  const double px_per_m = dpi / 0.0254;
  const Vec2 r0 = arc.start_m - arc.centre_m;
  const double radius = r0.norm(), from = std::atan2(r0.y(), r0.x());
  const double length = std::abs(arc.sweep_rad) * radius - 2.0 * trim_m;
  std::vector<Vec2> out;
  if (!(length > kStep_m)) {
    why = fmt::format("the arc ({:.2f} mm) is no longer than its trimmed ends", (std::abs(arc.sweep_rad) * radius) * 1e3);
    return out;
  }
  const int profiles = static_cast<int>(length / kStep_m) + 1;
  const int half_samples = static_cast<int>(std::ceil(half_width_m * px_per_m / kSample_px));
  const int ink_half = std::max(2, static_cast<int>(std::round(kInkHalf_m * px_per_m / kSample_px)));
  std::vector<double> values(static_cast<std::size_t>(2 * half_samples + 1)), sorted;
  const double sign = arc.sweep_rad >= 0.0 ? 1.0 : -1.0;
  // The ink's radial offset from the circle on one radial profile at `angle` (px outwards), or NaN.
  const auto offset_at = [&](double angle) {
    const Vec2 normal(std::cos(angle), std::sin(angle));
    const Vec2 on_circle = arc.centre_m + radius * normal;
    const Vec2 c_px = registration.to_scan(on_circle) * px_per_m;
    const Vec2 n_px = ((registration.to_scan(on_circle + 1e-4 * normal) - registration.to_scan(on_circle)) * px_per_m).normalized();
    for (int s = -half_samples; s <= half_samples; ++s) {
      const Vec2 p = c_px + (s * kSample_px) * n_px;
      const double g = sample(grey, p.x(), p.y());
      if (!std::isfinite(g)) return std::nan("");
      values[static_cast<std::size_t>(s + half_samples)] = g;
    }
    sorted = values;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const double paper = sorted[sorted.size() / 2];
    std::size_t darkest = 0;
    for (std::size_t s = 1; s < values.size(); ++s) {
      if (values[s] < values[darkest]) darkest = s;
    }
    if (!(paper - values[darkest] > 0.25 * paper)) return std::nan("");
    double sum = 0.0, moment = 0.0;
    const auto lo = static_cast<std::ptrdiff_t>(darkest) - ink_half, hi = static_cast<std::ptrdiff_t>(darkest) + ink_half;
    for (std::ptrdiff_t s = std::max<std::ptrdiff_t>(lo, 0); s <= std::min<std::ptrdiff_t>(hi, static_cast<std::ptrdiff_t>(values.size()) - 1); ++s) {
      const double ink = std::max(0.0, paper - values[static_cast<std::size_t>(s)]);
      sum += ink;
      moment += ink * static_cast<double>(s - half_samples) * kSample_px;
    }
    return moment / sum;
  };
  // Each point: the mean offset of five profiles a pixel apart along the arc (the paper's grain averages out), set
  // off radially from the circle in the robot frame (the registration is rigid: a scan pixel is 1/px_per_m there).
  const double pixel_rad = 1.0 / (px_per_m * radius);
  for (int k = 0; k < profiles; ++k) {
    const double angle = from + sign * (trim_m + k * kStep_m) / radius;
    double total = 0.0;
    int found = 0;
    for (int j = -2; j <= 2; ++j) {
      const double t = offset_at(angle + j * pixel_rad);
      if (std::isfinite(t)) total += t, ++found;
    }
    if (found < 3) continue;
    out.push_back(arc.centre_m + (radius + total / found / px_per_m) * Vec2(std::cos(angle), std::sin(angle)));
  }
  if (2 * out.size() < static_cast<std::size_t>(profiles)) {
    why = fmt::format("ink found on {} of its {} radial profiles", out.size(), profiles);
    out.clear();
  }
  return out;
}

}  // namespace stiffpath::vision::detail
