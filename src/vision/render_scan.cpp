// The synthetic scanner: places the path, draws the mark, adds blur, paper texture, shading, noise, specks; truth.
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render.hpp"

namespace stiffpath::vision {

namespace {

void check(const RenderOptions& o) {
  auto bad = [](const std::string& what) { throw Error("render: " + what); };
  if (!(o.dpi > 0.0) || !std::isfinite(o.dpi)) bad(fmt::format("dpi must be positive, got {}", o.dpi));
  if (!(o.mark_width_m > 0.0) || !std::isfinite(o.mark_width_m)) bad(fmt::format("mark width must be positive, got {} m", o.mark_width_m));
  if (!std::isfinite(o.rotation_rad)) bad("rotation must be finite");
  if (!(o.margin_m >= 0.0) || !std::isfinite(o.margin_m)) bad(fmt::format("margin must be >= 0, got {} m", o.margin_m));
  if (!(o.blur_px >= 0.0) || o.blur_px > 20.0) bad(fmt::format("blur must be in [0, 20] px, got {}", o.blur_px));
  if (!(o.noise >= 0.0) || o.noise > 1.0) bad(fmt::format("noise must be in [0, 1], got {}", o.noise));
  if (!(o.texture >= 0.0) || o.texture > 1.0) bad(fmt::format("texture must be in [0, 1], got {}", o.texture));
  if (!(o.shading >= 0.0) || o.shading >= 1.0) bad(fmt::format("shading must be in [0, 1), got {}", o.shading));
  if (!(o.paper_level > 0.0) || o.paper_level > 1.0) bad(fmt::format("paper level must be in (0, 1], got {}", o.paper_level));
  if (!(o.ink_level >= 0.0) || !(o.ink_level < o.paper_level)) bad(fmt::format("ink level must be in [0, paper level), got {}", o.ink_level));
  if (o.bit_depth != 8 && o.bit_depth != 16) bad(fmt::format("bit depth must be 8 or 16, got {}", o.bit_depth));
  if (o.specks < 0 || o.specks > 100000) bad(fmt::format("specks must be in [0, 100000], got {}", o.specks));
}

// Wood-fibre texture: Gaussian noise on a coarse grid stretched along x (fibres), smoothly upsampled, unit σ.
cv::Mat fibre_texture(int rows, int cols, cv::RNG& rng) {
  cv::Mat coarse(rows / 3 + 3, cols / 12 + 3, CV_32F);
  rng.fill(coarse, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat texture;
  cv::resize(coarse, texture, cv::Size(cols, rows), 0, 0, cv::INTER_CUBIC);
  cv::Scalar mean, sd;
  cv::meanStdDev(texture, mean, sd);
  texture = (texture - mean[0]) / std::max(sd[0], 1e-12);
  return texture;
}

}  // namespace

RenderedScan render_scan(const std::vector<std::vector<Point2>>& sides, bool closed, const RenderOptions& o) {
  check(o);
  if (sides.empty()) throw Error("render: no path to draw");
  const double px_per_m = o.dpi / 0.0254;
  const double c = std::cos(o.rotation_rad), s = std::sin(o.rotation_rad);
  Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  RenderedScan scan;
  for (const auto& side : sides) {
    if (side.size() < 2) throw Error("render: every side needs at least two points");
    std::vector<Point2> turned;
    for (const auto& p : side) {
      if (!p.allFinite()) throw Error("render: a path point is not finite");
      const Point2 q{c * p.x() - s * p.y(), s * p.x() + c * p.y()};
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
      turned.push_back(q);
    }
    scan.sides.push_back(std::move(turned));
  }
  const double pad = o.margin_m + o.mark_width_m / 2;
  const double width_px = std::ceil((hi.x() - lo.x() + 2 * pad) * px_per_m);
  const double height_px = std::ceil((hi.y() - lo.y() + 2 * pad) * px_per_m);
  if (width_px * height_px > 200e6) {
    throw Error(fmt::format("render: the image would be {:.0f} × {:.0f} px, above the 200 Mpx limit", width_px, height_px));
  }
  const int cols = static_cast<int>(width_px), rows = static_cast<int>(height_px);
  // Centre the path in the image.
  const Point2 shift = Point2{cols, rows} / (2 * px_per_m) - (lo + hi) / 2;
  std::vector<Point2> polyline_px;
  for (auto& side : scan.sides) {
    for (auto& p : side) {
      p += shift;
      polyline_px.push_back(p * px_per_m);
    }
  }
  scan.dpi = o.dpi;
  scan.mark_width_m = o.mark_width_m;
  scan.closed = closed;
  scan.truth = evaluation::measure_sides(scan.sides, closed, o.truth_options);

  cv::Mat coverage = cv::Mat::zeros(rows, cols, CV_32F);
  draw_stroke_coverage(coverage, polyline_px, o.mark_width_m * px_per_m / 2);
  if (o.blur_px > 0.0) cv::GaussianBlur(coverage, coverage, cv::Size(0, 0), o.blur_px);

  cv::RNG rng(o.seed);
  cv::Mat specks = cv::Mat::zeros(rows, cols, CV_32F);
  for (int i = 0; i < o.specks; ++i) {
    const Point2 at{rng.uniform(0.0, static_cast<double>(cols)), rng.uniform(0.0, static_cast<double>(rows))};
    const double radius = rng.uniform(1.0, 4.0), strength = rng.uniform(0.5, 0.9);
    const cv::Rect box(std::max(0, static_cast<int>(at.x() - 6)), std::max(0, static_cast<int>(at.y() - 6)), 13, 13);
    const cv::Rect clipped = box & cv::Rect(0, 0, cols, rows);
    cv::Mat local = cv::Mat::zeros(clipped.size(), CV_32F);
    draw_stroke_coverage(local, {at - Point2{clipped.x, clipped.y}}, radius);
    specks(clipped) = cv::max(specks(clipped), local * strength);
  }
  const cv::Mat texture = o.texture > 0.0 ? fibre_texture(rows, cols, rng) : cv::Mat::zeros(rows, cols, CV_32F);

  const double k = 1.0 - o.ink_level / o.paper_level;
  const double full_scale = o.bit_depth == 8 ? 255.0 : 65535.0;
  cv::Mat grey(rows, cols, o.bit_depth == 8 ? CV_8U : CV_16U);
  cv::Mat noise_row(1, cols, CV_32F);
  for (int y = 0; y < rows; ++y) {
    rng.fill(noise_row, cv::RNG::NORMAL, 0.0, 1.0);
    const float* cov = coverage.ptr<float>(y);
    const float* tex = texture.ptr<float>(y);
    const float* spk = specks.ptr<float>(y);
    const float* nz = noise_row.ptr<float>(0);
    const double yn = static_cast<double>(y) / rows;
    for (int x = 0; x < cols; ++x) {
      const double illumination = 1.0 - o.shading * (0.6 * x / cols + 0.4 * yn * yn);
      const double paper = o.paper_level * illumination * (1.0 + o.texture * tex[x]);
      const double v = paper * (1.0 - k * cov[x]) * (1.0 - k * spk[x]) + o.noise * nz[x];
      const double q = std::clamp(std::round(v * full_scale), 0.0, full_scale);
      if (o.bit_depth == 8) {
        grey.ptr<std::uint8_t>(y)[x] = static_cast<std::uint8_t>(q);
      } else {
        grey.ptr<std::uint16_t>(y)[x] = static_cast<std::uint16_t>(q);
      }
    }
  }
  if (o.colour) {
    // A warm paper tone; the grey conversion of this colour is proportional to the grey image.
    std::vector<cv::Mat> channels{grey * 0.90, grey * 0.97, grey.clone()};
    cv::merge(channels, scan.image);
  } else {
    scan.image = grey;
  }
  return scan;
}

}  // namespace stiffpath::vision
