// Benchmarks of the scan measurement and the synthetic scanner: seconds per pixel at 1200 dpi (target ≤ 60 ns/px for scans).
#include <benchmark/benchmark.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "stiffpath/evaluation/smoothing_spline.hpp"
#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace {
using namespace stiffpath;

// A 140 mm line at 1° on a 150 mm × 20 mm strip (7087 × 945 px, 6.7 Mpx) with noise, texture and shading.
const cv::Mat& strip() {
  static const cv::Mat image = [] {
    vision::RenderOptions o;
    o.rotation_rad = 0.0175;
    o.margin_m = 4.9e-3;
    o.texture = 0.01;
    o.specks = 20;
    const auto shape = vision::line_shape(0.140);
    const cv::Mat rendered = vision::render_scan(vision::sample_shape(shape, {}), false, o).image;
    const int rows = static_cast<int>(std::lround(0.020 / 0.0254 * 1200)), cols = static_cast<int>(std::lround(0.150 / 0.0254 * 1200));
    cv::Mat out;
    const int top = (rows - rendered.rows) / 2, left = (cols - rendered.cols) / 2;
    cv::copyMakeBorder(rendered, out, top, rows - rendered.rows - top, left, cols - rendered.cols - left, cv::BORDER_REFLECT);
    return out;
  }();
  return image;
}

void per_pixel(benchmark::State& state, const cv::Mat& image) {
  state.counters["px"] = static_cast<double>(image.total());
  state.counters["s_per_px"] = benchmark::Counter(static_cast<double>(image.total()),
                                                  benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_ScanStrip(benchmark::State& state) {
  const cv::Mat& image = strip();
  for (auto _ : state) benchmark::DoNotOptimize(vision::analyse_scan(image, 1200.0));
  per_pixel(state, image);
}
BENCHMARK(BM_ScanStrip)->Unit(benchmark::kMillisecond);

void BM_DecodeAndScanStripPng(benchmark::State& state) {
  std::vector<std::uint8_t> png;
  cv::imencode(".png", strip(), png);
  for (auto _ : state) {
    const cv::Mat image = cv::imdecode(png, cv::IMREAD_UNCHANGED);
    benchmark::DoNotOptimize(vision::analyse_scan(image, 1200.0));
  }
  per_pixel(state, strip());
}
BENCHMARK(BM_DecodeAndScanStripPng)->Unit(benchmark::kMillisecond);

void BM_ScanTriangle40mm(benchmark::State& state) {
  vision::RenderOptions o;
  o.texture = 0.01;
  const auto shape = vision::triangle_shape(0.040);
  const cv::Mat image = vision::render_scan(vision::sample_shape(shape, {}), true, o).image;
  vision::ScanOptions so;
  so.sides = 3;
  for (auto _ : state) benchmark::DoNotOptimize(vision::analyse_scan(image, 1200.0, so));
  per_pixel(state, image);
}
BENCHMARK(BM_ScanTriangle40mm)->Unit(benchmark::kMillisecond);

// A plate of 80 × 70 mm (12.5 Mpx at 1200 dpi) holding a y line, an x line, a triangle and three labels.
vision::Plate small_plate() {
  vision::Plate plate;
  plate.width_m = 80e-3, plate.height_m = 70e-3;
  auto moved = [](vision::PathShape shape, double dx, double dy, bool vertical) {
    if (vertical) {
      for (auto& v : shape.vertices) v = {-v.y(), v.x()};
    }
    for (auto& v : shape.vertices) v += vision::Point2{dx, dy};
    return vision::PlateMarkPath{vision::sample_shape(shape, {0.05e-3, 8e-3, 20e-3}), shape.closed};
  };
  plate.marks = {moved(vision::line_shape(50e-3), 8e-3, 12e-3, true), moved(vision::line_shape(40e-3), 20e-3, 64e-3, false),
                 moved(vision::triangle_shape(30e-3), 30e-3, 45e-3, false)};
  plate.labels = {{"Y 5G", {10e-3, 9e-3}, 3e-3}, {"X 5G OC", {20e-3, 60e-3}, 3e-3}, {"TRI", {62e-3, 50e-3}, 3e-3}};
  return plate;
}

vision::RenderOptions plate_options() {
  vision::RenderOptions o;
  o.texture = 0.01;
  o.specks = 20;
  return o;
}

// The synthetic scanner's band pipeline on the plate, into a sink that keeps nothing.
void BM_RenderPlateBands(benchmark::State& state) {
  const vision::Plate plate = small_plate();
  std::size_t pixels = 0;
  for (auto _ : state) {
    const auto rendered = vision::render_plate(plate, plate_options(), [&](int, const cv::Mat& rows) { pixels = rows.cols; });
    benchmark::DoNotOptimize(rendered.marks.size());
  }
  const cv::Size size{static_cast<int>(std::ceil(0.080 / 0.0254 * 1200)), static_cast<int>(std::ceil(0.070 / 0.0254 * 1200))};
  per_pixel(state, cv::Mat(size, CV_8U));
  benchmark::DoNotOptimize(pixels);
}
BENCHMARK(BM_RenderPlateBands)->Unit(benchmark::kMillisecond);

// Every mark of the plate: features, shapes, cross-sections.
void BM_ScanPlateAllMarks(benchmark::State& state) {
  const cv::Mat image = vision::render_plate(small_plate(), plate_options()).image;
  vision::ScanOptions o;
  o.sides = 0;
  for (auto _ : state) benchmark::DoNotOptimize(vision::analyse_plate(image, 1200.0, o));
  per_pixel(state, image);
}
BENCHMARK(BM_ScanPlateAllMarks)->Unit(benchmark::kMillisecond);

void BM_SmoothingSpline7000(benchmark::State& state) {
  std::vector<double> t(7000), y(7000);
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = 2.1167e-5 * static_cast<double>(i), y[i] = 1e-6 * std::sin(0.01 * static_cast<double>(i));
  for (auto _ : state) benchmark::DoNotOptimize(evaluation::SmoothingSpline::fit(t, y, 1e-3));
}
BENCHMARK(BM_SmoothingSpline7000)->Unit(benchmark::kMicrosecond);

}  // namespace
