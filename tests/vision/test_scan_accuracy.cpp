// Accuracy of the scan measurement on rendered scans with known truth: lines, wiggles, triangles, image variants.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "stiffpath/vision/render/render.hpp"
#include "stiffpath/vision/scan/scan.hpp"

namespace stiffpath::vision {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

struct Case {
  double size_mm, angle_deg;
  std::uint64_t seed;
  Wiggle wiggle{};
};

// The conditions: 1200 dpi, 0.2 mm mark, blur σ 0.8 px, 1 % pixel noise, 1 % fibre texture, 8 % shading.
RenderOptions scan_options(const Case& c) {
  RenderOptions o;
  o.rotation_rad = c.angle_deg * kDeg;
  o.seed = c.seed;
  o.noise = 0.01;
  o.texture = 0.01;
  o.margin_m = 1.2e-3;  // narrow strips keep the suite fast
  return o;
}

ScanResult measure(const RenderedScan& scan, int sides) {
  ScanOptions so;
  so.sides = sides;
  if (scan.image.channels() == 1) return analyse_scan(scan.image, scan.dpi, so);
  cv::Mat grey;
  cv::cvtColor(scan.image, grey, cv::COLOR_BGR2GRAY);  // as load_scan does for colour files
  return analyse_scan(grey, scan.dpi, so);
}

TEST(ScanAccuracy, LinesOf100And150MmWithin5Micrometres) {
  const Case cases[] = {{100, -3.0, 1}, {100, 0.0, 2}, {100, 1.7, 3}, {150, 3.0, 4}, {150, -0.6, 5}, {150, 2.2, 6}};
  for (const auto& c : cases) {
    const auto scan = render_scan(sample_shape(line_shape(c.size_mm * 1e-3), {}), false, scan_options(c));
    const auto r = measure(scan, 1);
    const double err_um = (r.metrics.length_m - scan.truth.length_m) * 1e6;
    std::printf("[accuracy] line %.0f mm at %+.1f deg (seed %llu): length error %+.2f um, width error %+.2f um, "
                "area %.4f mm2, max deviation %.2f um\n", c.size_mm, c.angle_deg, static_cast<unsigned long long>(c.seed),
                err_um, (r.width_m - scan.mark_width_m) * 1e6, r.metrics.deviation_area_m2 * 1e6, r.metrics.max_deviation_m * 1e6);
    EXPECT_LE(std::abs(err_um), 5.0) << c.size_mm << " mm at " << c.angle_deg << "°";
    EXPECT_LE(std::abs(r.width_m - scan.mark_width_m), 2e-6);
    EXPECT_LT(r.metrics.max_deviation_m, 3e-6);  // the noise floor of a straight mark
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  }
}

TEST(ScanAccuracy, WigglyLinesDeviationAreaWithin3Percent) {
  const Case cases[] = {{100, 1.2, 7, {5e-5, 10e-3, 40e-3}}, {150, -2.5, 8, {8e-5, 15e-3, 60e-3}}, {100, 0.3, 9, {5e-5, 6e-3, 30e-3}}};
  for (const auto& c : cases) {
    const auto scan = render_scan(sample_shape(line_shape(c.size_mm * 1e-3), c.wiggle), false, scan_options(c));
    const auto r = measure(scan, 1);
    const double rel = r.metrics.deviation_area_m2 / scan.truth.deviation_area_m2 - 1;
    const double len_um = (r.metrics.length_m - scan.truth.length_m) * 1e6;
    std::printf("[accuracy] wiggly line %.0f mm, amplitude %.2f mm, wavelength %.0f mm: area %.4f mm2 vs %.4f mm2 (%+.2f %%), "
                "max deviation %.4f vs %.4f mm, length error %+.2f um\n", c.size_mm, c.wiggle.amplitude_m * 1e3,
                c.wiggle.wavelength_m * 1e3, r.metrics.deviation_area_m2 * 1e6, scan.truth.deviation_area_m2 * 1e6, 100 * rel,
                r.metrics.max_deviation_m * 1e3, scan.truth.max_deviation_m * 1e3, len_um);
    EXPECT_LE(std::abs(rel), 0.03);
    EXPECT_NEAR(r.metrics.max_deviation_m, scan.truth.max_deviation_m, 0.05 * scan.truth.max_deviation_m);
    EXPECT_LE(std::abs(len_um), 5.0);
  }
}

TEST(ScanAccuracy, TriangleSidesWithin10Micrometres) {
  const Case cases[] = {{40, 1.3, 10}, {30, -2.0, 11, {5e-5, 8e-3, 30e-3}}};
  for (const auto& c : cases) {
    const auto scan = render_scan(sample_shape(triangle_shape(c.size_mm * 1e-3), c.wiggle), true, scan_options(c));
    const auto r = measure(scan, 3);
    ASSERT_TRUE(r.metrics.closed);
    ASSERT_EQ(r.metrics.sides.size(), 3u);
    ASSERT_EQ(r.metrics.corners.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      const auto& got = r.metrics.sides[k];
      const auto& want = scan.truth.sides[k];
      EXPECT_LT((got.start - want.start).norm(), 2e-5) << "side " << k << " is not the same side";
      const double err_um = (got.length_m - want.length_m) * 1e6;
      std::printf("[accuracy] triangle %.0f mm side %d: length error %+.2f um, corner error %.2f um\n", c.size_mm, k + 1,
                  err_um, (r.metrics.corners[k].position - scan.truth.corners[k].position).norm() * 1e6);
      EXPECT_LE(std::abs(err_um), 10.0);
      EXPECT_NEAR(r.metrics.corners[k].angle_rad, scan.truth.corners[k].angle_rad, 1e-3);
    }
    if (c.wiggle.amplitude_m > 0) {
      const double rel = r.metrics.deviation_area_m2 / scan.truth.deviation_area_m2 - 1;
      std::printf("[accuracy] triangle %.0f mm with wiggle: total area %+.2f %%\n", c.size_mm, 100 * rel);
      EXPECT_LE(std::abs(rel), 0.03);
    }
  }
}

TEST(ScanAccuracy, SixteenBitColourBlurThinMarksAndSpecks) {
  struct Variant {
    const char* name;
    RenderOptions o;
  };
  std::vector<Variant> variants;
  const Case base{60, 0.8, 12};
  auto add = [&](const char* name, auto tweak) {
    RenderOptions o = scan_options(base);
    tweak(o);
    variants.push_back({name, o});
  };
  add("16-bit", [](RenderOptions& o) { o.bit_depth = 16; });
  add("colour", [](RenderOptions& o) { o.colour = true; });
  add("blur 1.5 px", [](RenderOptions& o) { o.blur_px = 1.5; });
  add("0.1 mm mark", [](RenderOptions& o) { o.mark_width_m = 0.1e-3; });
  add("0.4 mm mark", [](RenderOptions& o) { o.mark_width_m = 0.4e-3; });
  add("40 specks", [](RenderOptions& o) { o.specks = 40; });
  add("strong shading", [](RenderOptions& o) { o.shading = 0.3; });
  for (const auto& v : variants) {
    const auto scan = render_scan(sample_shape(line_shape(base.size_mm * 1e-3), {}), false, v.o);
    const auto r = measure(scan, 1);
    const double err_um = (r.metrics.length_m - scan.truth.length_m) * 1e6;
    std::printf("[accuracy] %s: length error %+.2f um, width error %+.2f um\n", v.name, err_um,
                (r.width_m - scan.mark_width_m) * 1e6);
    EXPECT_LE(std::abs(err_um), 5.0) << v.name;
    EXPECT_LE(std::abs(r.width_m - scan.mark_width_m), 3e-6) << v.name;
    if (v.o.specks > 0) {
      ASSERT_GT(r.specks_ignored, 0);
      EXPECT_EQ(r.warnings.back(), "ignored " + std::to_string(r.specks_ignored) + " dust speck(s)");
    }
  }
}

}  // namespace
}  // namespace stiffpath::vision
