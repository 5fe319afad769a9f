// The synthetic scanner's image, made band by band: coverage, blur, specks, fibre texture, shading, noise, quantisation.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "render_internal.hpp"
#include "render_sheet.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision::detail {

namespace {

constexpr int kBand = 64;  // rows per band

// Cubic interpolation (a = −0.75, as OpenCV's INTER_CUBIC) of a coarse grid onto `n` output samples:
// for each output, the first of its four source taps (clamped to the grid) and their weights.
struct CubicTaps {
  std::vector<int> index;      // 4 per output
  std::vector<float> weight;   // 4 per output
  double mean_square = 0;      // mean over outputs of Σ (weights on one source sample)²: the variance of unit noise
};

CubicTaps cubic_taps(int n, int source) {
  CubicTaps t;
  t.index.resize(4 * static_cast<std::size_t>(n));
  t.weight.resize(4 * static_cast<std::size_t>(n));
  const double scale = static_cast<double>(source) / n, a = -0.75;
  for (int i = 0; i < n; ++i) {
    const double f = (i + 0.5) * scale - 0.5;
    const int i0 = static_cast<int>(std::floor(f));
    const double x = f - i0;
    const double w[4] = {((a * (x + 1) - 5 * a) * (x + 1) + 8 * a) * (x + 1) - 4 * a, ((a + 2) * x - (a + 3)) * x * x + 1,
                         ((a + 2) * (1 - x) - (a + 3)) * (1 - x) * (1 - x) + 1, 0.0};
    const double w3 = 1.0 - w[0] - w[1] - w[2];
    double squares = 0;
    int last = -1;
    double run = 0;
    for (int k = 0; k < 4; ++k) {
      const int idx = std::clamp(i0 - 1 + k, 0, source - 1);
      const double wk = k == 3 ? w3 : w[k];
      t.index[4 * static_cast<std::size_t>(i) + k] = idx;
      t.weight[4 * static_cast<std::size_t>(i) + k] = static_cast<float>(wk);
      if (idx != last && last >= 0) squares += run * run, run = 0;
      run += wk;
      last = idx;
    }
    squares += run * run;
    t.mean_square += squares / n;
  }
  return t;
}

struct Speck {
  Point2 at;
  double radius, strength;
};

}  // namespace

void check_image_size(double width_px, double height_px) {
  if (!(width_px * height_px <= kMaxRenderPixels)) {
    throw Error(fmt::format("render: the image would be {:.0f} × {:.0f} px, above the {:.0f} Mpx limit", width_px, height_px,
                            kMaxRenderPixels / 1e6));
  }
}

void check_path_points(double points, const std::string& what) {
  if (!(points <= static_cast<double>(kMaxRenderPathPoints))) {
    throw Error(fmt::format("render: {} would take {:.4g} points, above the budget of {} points of path for one render", what,
                            points, kMaxRenderPathPoints));
  }
}

cv::Mat label_coverage(const Scene::Text& label, int thickness, cv::Point& origin) {
  const int height = static_cast<int>(std::lround(label.height_px));
  const double scale = cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, height, thickness);
  int baseline = 0;
  const cv::Size size = cv::getTextSize(label.text, cv::FONT_HERSHEY_SIMPLEX, scale, thickness, &baseline);
  const int pad = thickness + 2;
  origin = cv::Point(pad, pad + size.height);
  cv::Mat letters = cv::Mat::zeros(size.height + baseline + 2 * pad, size.width + 2 * pad, CV_8U);
  cv::putText(letters, label.text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255), thickness, cv::LINE_AA);
  cv::Mat coverage;
  letters.convertTo(coverage, CV_32F, 1.0 / 255);
  return coverage;
}

void rasterise(const Scene& scene, const RenderOptions& o, const RowSink& sink) {
  const int rows = scene.rows, cols = scene.cols;
  cv::RNG rng(o.seed);
  std::vector<Speck> specks;
  for (int i = 0; i < o.specks; ++i) {
    const Point2 at{rng.uniform(0.0, static_cast<double>(cols)), rng.uniform(0.0, static_cast<double>(rows))};
    const double radius = rng.uniform(1.0, 4.0), strength = rng.uniform(0.5, 0.9);
    specks.push_back({at, radius, strength});
  }
  // Wood-fibre texture: unit Gaussian noise on a grid of 12 × 3 px cells stretched along x (fibres),
  // interpolated cubically and scaled to unit variance.
  cv::Mat coarse;
  CubicTaps tx, ty;
  float texture_scale = 0;
  if (o.texture > 0.0) {
    coarse.create(rows / 3 + 3, cols / 12 + 3, CV_32F);
    rng.fill(coarse, cv::RNG::NORMAL, 0.0, 1.0);
    tx = cubic_taps(cols, coarse.cols);
    ty = cubic_taps(rows, coarse.rows);
    texture_scale = static_cast<float>(1.0 / std::sqrt(tx.mean_square * ty.mean_square));
  }

  const StrokeRaster strokes(scene.strokes_px, scene.radius_px);
  const int halo = o.blur_px > 0.0 ? static_cast<int>(std::ceil(4 * o.blur_px)) + 2 : 0;
  const double k = 1.0 - o.ink_level / o.paper_level;
  const double full_scale = o.bit_depth == 8 ? 255.0 : 65535.0;
  const int depth = o.bit_depth == 8 ? CV_8U : CV_16U;
  cv::Mat noise_row(1, cols, CV_32F), coarse_row(1, std::max(coarse.cols, 1), CV_32F), texture_row(1, cols, CV_32F, cv::Scalar(0));
  SheetRow sheet;
  for (int y0 = 0; y0 < rows; y0 += kBand) {
    const int y1 = std::min(rows, y0 + kBand);
    // Coverage of the band and its halo, so the blur sees the rows beyond the band (at the image's top
    // and bottom it stops there, as a whole-image blur would).
    const int c0 = std::max(0, y0 - halo), c1 = std::min(rows, y1 + halo);
    cv::Mat coverage = cv::Mat::zeros(c1 - c0, cols, CV_32F);
    strokes.draw(coverage, c0);
    if (!scene.labels.empty()) {
      cv::Mat letters = cv::Mat::zeros(coverage.size(), CV_8U);
      const int thickness = std::max(1, static_cast<int>(std::lround(2 * scene.radius_px)));
      for (const auto& label : scene.labels) {
        const double scale = cv::getFontScaleFromHeight(cv::FONT_HERSHEY_SIMPLEX, static_cast<int>(std::lround(label.height_px)), thickness);
        if (label.at_px.y() + thickness < c0 || label.at_px.y() - label.height_px - thickness > c1) continue;
        cv::putText(letters, label.text, cv::Point(static_cast<int>(std::lround(label.at_px.x())), static_cast<int>(std::lround(label.at_px.y())) - c0),
                    cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255), thickness, cv::LINE_AA);
      }
      cv::Mat as_float;
      letters.convertTo(as_float, CV_32F, 1.0 / 255);
      coverage = cv::max(coverage, as_float);
    }
    for (const auto& sprite : scene.sprites) {
      const cv::Rect in_image = cv::Rect(sprite.at, sprite.coverage.size()) & cv::Rect(0, c0, cols, c1 - c0);
      if (in_image.empty()) continue;
      cv::Mat into = coverage(in_image - cv::Point(0, c0));
      cv::max(into, sprite.coverage(in_image - sprite.at), into);
    }
    if (o.blur_px > 0.0) cv::GaussianBlur(coverage, coverage, cv::Size(0, 0), o.blur_px);
    cv::Mat dust = cv::Mat::zeros(y1 - y0, cols, CV_32F);
    for (const auto& s : specks) {
      if (s.at.y() + 7 < y0 || s.at.y() - 7 > y1) continue;
      const cv::Rect box(std::max(0, static_cast<int>(s.at.x() - 6)), std::max(0, static_cast<int>(s.at.y() - 6)), 13, 13);
      const cv::Rect clipped = box & cv::Rect(0, y0, cols, y1 - y0);
      if (clipped.empty()) continue;
      cv::Mat local = cv::Mat::zeros(clipped.size(), CV_32F);
      StrokeRaster({{s.at - Point2{clipped.x, clipped.y}}}, s.radius).draw(local, 0);
      const cv::Rect in_band = clipped - cv::Point(0, y0);
      dust(in_band) = cv::max(dust(in_band), local * s.strength);
    }

    cv::Mat smudges;
    if (scene.sheet) {
      smudges = cv::Mat::zeros(y1 - y0, cols, CV_32F);
      draw_smudges(*scene.sheet, y0, smudges);
    }
    cv::Mat out(y1 - y0, cols, CV_MAKETYPE(depth, o.colour ? 3 : 1));
    for (int y = y0; y < y1; ++y) {
      rng.fill(noise_row, cv::RNG::NORMAL, 0.0, 1.0);
      if (o.texture > 0.0) {
        float* cr = coarse_row.ptr<float>(0);
        const int* iy = &ty.index[4 * static_cast<std::size_t>(y)];
        const float* wy = &ty.weight[4 * static_cast<std::size_t>(y)];
        for (int x = 0; x < coarse.cols; ++x) {
          cr[x] = wy[0] * coarse.at<float>(iy[0], x) + wy[1] * coarse.at<float>(iy[1], x) + wy[2] * coarse.at<float>(iy[2], x) +
                  wy[3] * coarse.at<float>(iy[3], x);
        }
        float* tr = texture_row.ptr<float>(0);
        for (int x = 0; x < cols; ++x) {
          const int* ix = &tx.index[4 * static_cast<std::size_t>(x)];
          const float* wx = &tx.weight[4 * static_cast<std::size_t>(x)];
          tr[x] = texture_scale * (wx[0] * cr[ix[0]] + wx[1] * cr[ix[1]] + wx[2] * cr[ix[2]] + wx[3] * cr[ix[3]]);
        }
      }
      const float* cov = coverage.ptr<float>(y - c0);
      const float* tex = texture_row.ptr<float>(0);
      const float* spk = dust.ptr<float>(y - y0);
      const float* nz = noise_row.ptr<float>(0);
      const double yn = static_cast<double>(y) / rows;
      if (scene.sheet) sheet_row(*scene.sheet, y, cols, smudges.ptr<float>(y - y0), sheet);
      for (int x = 0; x < cols; ++x) {
        const double illumination = 1.0 - o.shading * (0.6 * x / cols + 0.4 * yn * yn);
        double paper = o.paper_level * illumination * (1.0 + o.texture * tex[x]);
        if (scene.sheet) {
          // On a bed: the page's share of the pixel is paper (curled, smudged), the rest the lid and its shadow.
          const auto i = static_cast<std::size_t>(x);
          paper = sheet.page[i] * paper * sheet.paper[i] + (1.0 - sheet.page[i]) * illumination * sheet.lid[i];
        }
        const double v = paper * (1.0 - k * cov[x]) * (1.0 - k * spk[x]) + o.noise * nz[x];
        const double q = std::clamp(std::round(v * full_scale), 0.0, full_scale);
        if (o.colour) {
          // A warm paper tone; the grey conversion of this colour is proportional to the grey image.
          const double bgr[3] = {q * 0.90, q * 0.97, q};
          for (int c = 0; c < 3; ++c) {
            if (depth == CV_8U) {
              out.ptr<std::uint8_t>(y - y0)[3 * x + c] = cv::saturate_cast<std::uint8_t>(bgr[c]);
            } else {
              out.ptr<std::uint16_t>(y - y0)[3 * x + c] = cv::saturate_cast<std::uint16_t>(bgr[c]);
            }
          }
        } else if (depth == CV_8U) {
          out.ptr<std::uint8_t>(y - y0)[x] = static_cast<std::uint8_t>(q);
        } else {
          out.ptr<std::uint16_t>(y - y0)[x] = static_cast<std::uint16_t>(q);
        }
      }
    }
    sink(y0, out);
    if (o.progress) o.progress(static_cast<double>(y1) / rows);
  }
}

cv::Mat rasterise_image(const Scene& scene, const RenderOptions& o) {
  cv::Mat image(scene.rows, scene.cols, CV_MAKETYPE(o.bit_depth == 8 ? CV_8U : CV_16U, o.colour ? 3 : 1));
  rasterise(scene, o, [&](int first_row, const cv::Mat& rows) { rows.copyTo(image.rowRange(first_row, first_row + rows.rows)); });
  return image;
}

}  // namespace stiffpath::vision::detail
