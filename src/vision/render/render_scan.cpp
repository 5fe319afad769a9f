// The synthetic scanner: places a path on the image, works out the truth, rasterises.
#include <cmath>
#include <fmt/format.h>

#include "render_internal.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision {

namespace detail {

void check_render_options(const RenderOptions& o) {
  auto bad = [](const std::string& what) { throw Error("render: " + what); };
  if (!(o.dpi > 0.0) || !std::isfinite(o.dpi) || o.dpi > 1e5) bad(fmt::format("dpi must be in (0, 100000], got {}", o.dpi));
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

}  // namespace detail

namespace {

// Rotates the sides, places them margin_m inside an image just large enough (centred), and returns the
// scene and the placed sides (m, image frame).
detail::Scene place(const std::vector<std::vector<Point2>>& sides, const RenderOptions& o, std::vector<std::vector<Point2>>& placed) {
  if (sides.empty()) throw Error("render: no path to draw");
  const double px_per_m = o.dpi / 0.0254;
  const double c = std::cos(o.rotation_rad), s = std::sin(o.rotation_rad);
  Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  placed.clear();
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
    placed.push_back(std::move(turned));
  }
  const double pad = o.margin_m + o.mark_width_m / 2;
  const double width_px = std::ceil((hi.x() - lo.x() + 2 * pad) * px_per_m);
  const double height_px = std::ceil((hi.y() - lo.y() + 2 * pad) * px_per_m);
  detail::check_image_size(width_px, height_px);
  detail::Scene scene;
  scene.cols = static_cast<int>(width_px);
  scene.rows = static_cast<int>(height_px);
  scene.radius_px = o.mark_width_m * px_per_m / 2;
  const Point2 shift = Point2{scene.cols, scene.rows} / (2 * px_per_m) - (lo + hi) / 2;
  std::vector<Point2> polyline;
  for (auto& side : placed) {
    for (auto& p : side) {
      p += shift;
      polyline.push_back(p * px_per_m);
    }
  }
  scene.strokes_px.push_back(std::move(polyline));
  return scene;
}

// The scan's metadata and ground truth, and the scene its image is made from.
detail::Scene prepare(const std::vector<std::vector<Point2>>& sides, bool closed, const RenderOptions& o, RenderedScan& scan) {
  detail::check_render_options(o);
  const detail::Scene scene = place(sides, o, scan.sides);
  scan.dpi = o.dpi;
  scan.mark_width_m = o.mark_width_m;
  scan.closed = closed;
  scan.truth = evaluation::measure_sides(scan.sides, closed, o.truth_options);
  return scene;
}
}  // namespace

cv::Size rendered_size(const std::vector<std::vector<Point2>>& sides, const RenderOptions& o) {
  detail::check_render_options(o);
  std::vector<std::vector<Point2>> placed;
  const detail::Scene scene = place(sides, o, placed);
  return {scene.cols, scene.rows};
}

RenderedScan render_scan(const std::vector<std::vector<Point2>>& sides, bool closed, const RenderOptions& o, const RowSink& sink) {
  RenderedScan scan;
  detail::rasterise(prepare(sides, closed, o, scan), o, sink);
  return scan;
}

RenderedScan render_scan(const std::vector<std::vector<Point2>>& sides, bool closed, const RenderOptions& o) {
  RenderedScan scan;
  scan.image = detail::rasterise_image(prepare(sides, closed, o, scan), o);
  return scan;
}

}  // namespace stiffpath::vision
