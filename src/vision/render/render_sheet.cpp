// The page on a scanner's bed, row by row: the page's share of each pixel, its curled edge, smudges, the lid and the edge's shadow.
#include "render_sheet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stiffpath::vision::detail {

void sheet_row(const Sheet& sheet, int y, int cols, const float* smudge, SheetRow& row) {
  row.page.resize(static_cast<std::size_t>(cols));
  row.paper.resize(static_cast<std::size_t>(cols));
  row.lid.resize(static_cast<std::size_t>(cols));
  const double shadow_px = std::max(sheet.bed.edge_shadow_m * sheet.px_per_m, 1e-6);
  const double curl_px = sheet.bed.curl_m * sheet.px_per_m;
  const double blur = sheet.edge_blur_px, reach = 5 * blur + 1;
  const double w = sheet.width_px, h = sheet.height_px;
  for (int x = 0; x < cols; ++x) {
    const Point2 p = sheet.to_page * (Point2{x + 0.5, y + 0.5} - sheet.origin_px);
    const double dx = std::max({0.0, -p.x(), p.x() - w}), dy = std::max({0.0, -p.y(), p.y() - h});
    const double outside = std::hypot(dx, dy);
    const double inside = std::min({p.x(), w - p.x(), p.y(), h - p.y()});
    const double signed_distance = outside > 0 ? outside : -inside;  // px, > 0 off the page
    // The page's share: a step blurred like everything the scanner sees.
    double page = signed_distance < -reach ? 1.0 : (signed_distance > reach ? 0.0 : 0.5 * std::erfc(signed_distance / (std::numbers::sqrt2 * blur)));
    // Paper lifted off the glass near its edge is lit less; smudges lie on it.
    double paper = 1.0;
    if (curl_px > 0 && inside > 0 && inside < curl_px) paper -= sheet.bed.curl_shading * (1 - inside / curl_px) * (1 - inside / curl_px);
    if (smudge != nullptr) paper *= 1.0 - smudge[x];
    // The lid, with the page's shadow along its edge.
    const double shade = signed_distance <= 0 ? 1.0 : std::max(0.0, 1.0 - signed_distance / shadow_px);
    row.page[static_cast<std::size_t>(x)] = static_cast<float>(page);
    row.paper[static_cast<std::size_t>(x)] = static_cast<float>(paper);
    row.lid[static_cast<std::size_t>(x)] = static_cast<float>(sheet.bed.lid_level * (1.0 - sheet.bed.edge_shadow * shade));
  }
}

void draw_smudges(const Sheet& sheet, int y0, cv::Mat& band) {
  for (const Smudge& s : sheet.smudges) {
    const double reach = 3.5 * std::max(s.sigma_a, s.sigma_b);
    const int top = std::max(y0, static_cast<int>(std::floor(s.centre.y() - reach)));
    const int bottom = std::min(y0 + band.rows - 1, static_cast<int>(std::ceil(s.centre.y() + reach)));
    const int left = std::max(0, static_cast<int>(std::floor(s.centre.x() - reach)));
    const int right = std::min(band.cols - 1, static_cast<int>(std::ceil(s.centre.x() + reach)));
    const double c = std::cos(s.angle_rad), sn = std::sin(s.angle_rad);
    for (int y = top; y <= bottom; ++y) {
      float* row = band.ptr<float>(y - y0);
      for (int x = left; x <= right; ++x) {
        const double rx = x + 0.5 - s.centre.x(), ry = y + 0.5 - s.centre.y();
        const double u = (c * rx + sn * ry) / s.sigma_a, v = (-sn * rx + c * ry) / s.sigma_b;
        const double d = s.strength * std::exp(-0.5 * (u * u + v * v));
        row[x] = static_cast<float>(1.0 - (1.0 - row[x]) * (1.0 - d));  // smudges over smudges darken further
      }
    }
  }
}

std::vector<Smudge> scatter_smudges(const Sheet& sheet, int count, cv::RNG& rng) {
  std::vector<Smudge> out;
  const Eigen::Matrix2d to_image = sheet.to_page.inverse();
  const double mm = sheet.px_per_m * 1e-3;
  for (int i = 0; i < count; ++i) {
    Smudge s;
    const double across = rng.uniform(1.0, 5.0) * mm / 2;  // 1–5 mm across (about ±1σ)
    s.sigma_a = across * rng.uniform(1.0, 2.5);            // elongated, as a finger's or a sleeve's
    s.sigma_b = across;
    s.angle_rad = rng.uniform(0.0, std::numbers::pi);
    s.strength = rng.uniform(0.02, 0.08);
    const Point2 on_page{rng.uniform(0.05, 0.95) * sheet.width_px, rng.uniform(0.05, 0.95) * sheet.height_px};
    s.centre = sheet.origin_px + to_image * on_page;
    out.push_back(s);
  }
  return out;
}

}  // namespace stiffpath::vision::detail
