// The synthetic scanner for plates: marks, fiducials and labels on a page, the page placed on a scanner's bed, each mark's truth.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "render_internal.hpp"
#include "render_sheet.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision {

PagePlacement page_placement(const ScannerBed* bed) {
  PagePlacement p;
  if (bed == nullptr) return p;
  const double c = std::cos(bed->page_angle_rad), s = std::sin(bed->page_angle_rad);
  p.linear << c, -s, s, c;  // x towards y: clockwise on screen
  p.offset = bed->page_at_m;
  if (bed->mirror) {  // x → width − x, after the placement
    p.linear.row(0) *= -1.0;
    p.offset.x() = bed->width_m - p.offset.x();
  }
  return p;
}

cv::Size plate_image_size(const Plate& plate, const RenderOptions& o) {
  detail::check_render_options(o);
  const double px_per_m = o.dpi / 0.0254;
  const double w = plate.bed ? plate.bed->width_m : plate.width_m, h = plate.bed ? plate.bed->height_m : plate.height_m;
  if (!(w > 0.0) || !(h > 0.0) || !std::isfinite(w * h)) {
    throw Error(fmt::format("render: the {} must have a positive size, got {} × {} mm", plate.bed ? "bed" : "page", w * 1e3, h * 1e3));
  }
  const double width_px = std::ceil(w * px_per_m), height_px = std::ceil(h * px_per_m);
  detail::check_image_size(width_px, height_px);
  return {static_cast<int>(width_px), static_cast<int>(height_px)};
}

namespace {

std::string mark_name(const PlateMarkPath& mark, std::size_t k) {
  return mark.id.empty() ? fmt::format("mark {}", k + 1) : fmt::format("mark {} ('{}')", k + 1, mark.id);
}

// A refusal at the plate file's entry when it came from one ("file:line:column: ..."), else "render: ...".
[[noreturn]] void refuse(const SourceLocation& where, const std::string& message) {
  if (where.file.empty()) throw Error("render: " + message);
  throw Error(where, message);
}

// The ring (closed, sampled every ≤ 20 µm) and the cross's two strokes of a fiducial at `at` (page frame, m).
std::vector<std::vector<Point2>> fiducial_strokes(const PlateFiducial& f) {
  const double r = f.shape.ring_radius_m;
  const int n = std::max(64, static_cast<int>(std::ceil(2 * std::numbers::pi * r / 20e-6)));
  std::vector<Point2> ring;
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    ring.push_back(f.at_m + r * Point2{std::cos(a), std::sin(a)});
  }
  std::vector<std::vector<Point2>> out{ring};
  if (f.shape.cross) {
    const double h = f.shape.cross_arm_m;
    out.push_back({f.at_m + Point2{-h, 0}, f.at_m + Point2{h, 0}});
    out.push_back({f.at_m + Point2{0, -h}, f.at_m + Point2{0, h}});
  }
  return out;
}

// Checks that every point of `sides`, widened by the mark's half width r, lies on the page; returns its box.
cv::Rect2d on_page(const std::vector<std::vector<Point2>>& sides, const Plate& plate, double r, const std::string& name,
                   const SourceLocation& where) {
  Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const auto& side : sides) {
    if (side.size() < 2) refuse(where, fmt::format("a side of {} has fewer than two points", name));
    for (const auto& p : side) {
      if (!p.allFinite()) refuse(where, fmt::format("a point of {} is not finite", name));
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  }
  if (lo.x() - r < 0 || lo.y() - r < 0 || hi.x() + r > plate.width_m || hi.y() + r > plate.height_m) {
    refuse(where, fmt::format("{} (x {:.2f}..{:.2f} mm, y {:.2f}..{:.2f} mm) does not fit on the {:.1f} × {:.1f} mm page", name,
                              lo.x() * 1e3, hi.x() * 1e3, lo.y() * 1e3, hi.y() * 1e3, plate.width_m * 1e3, plate.height_m * 1e3));
  }
  return {lo.x(), lo.y(), hi.x() - lo.x(), hi.y() - lo.y()};
}

// Moves page points (m) into the image (m), checking they land on it.
std::vector<std::vector<Point2>> placed(const std::vector<std::vector<Point2>>& sides, const PagePlacement& at, const cv::Size2d& image_m,
                                        double r, const std::string& name, const SourceLocation& where) {
  std::vector<std::vector<Point2>> out;
  for (const auto& side : sides) {
    std::vector<Point2> moved;
    moved.reserve(side.size());
    for (const auto& p : side) {
      const Point2 q = at.apply(p);
      if (q.x() - r < 0 || q.y() - r < 0 || q.x() + r > image_m.width || q.y() + r > image_m.height) {
        refuse(where, fmt::format("{} lies off the scanner's bed (at x = {:.2f} mm, y = {:.2f} mm of the bed)", name, q.x() * 1e3,
                                  q.y() * 1e3));
      }
      moved.push_back(q);
    }
    out.push_back(std::move(moved));
  }
  return out;
}

cv::Rect2d box_of(const std::vector<std::vector<Point2>>& sides) {
  Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const auto& side : sides) {
    for (const auto& p : side) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  return {lo.x(), lo.y(), hi.x() - lo.x(), hi.y() - lo.y()};
}

// A label drawn upright and turned onto the image by the placement (page px → image px).
detail::Scene::Sprite label_sprite(const detail::Scene::Text& label, int thickness, const PagePlacement& at, double px_per_m) {
  cv::Point origin;
  const cv::Mat upright = detail::label_coverage(label, thickness, origin);
  // Upright canvas pixel c maps to page px label.at_px + (c − origin), then to image px.
  const Point2 canvas_origin = label.at_px - Point2{origin.x, origin.y};
  const Point2 shift = at.offset * px_per_m + at.linear * canvas_origin;
  Point2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const Point2& c : {Point2{0, 0}, Point2{upright.cols, 0}, Point2{0, upright.rows}, Point2{upright.cols, upright.rows}}) {
    const Point2 q = shift + at.linear * c;
    lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  }
  detail::Scene::Sprite sprite;
  sprite.at = cv::Point(static_cast<int>(std::floor(lo.x())), static_cast<int>(std::floor(lo.y())));
  const cv::Size size(static_cast<int>(std::ceil(hi.x())) - sprite.at.x, static_cast<int>(std::ceil(hi.y())) - sprite.at.y);
  // warpAffine maps source pixel centres: image = A·canvas + (shift − at) with centres at +0.5 on both sides.
  const Point2 t = shift - Point2{sprite.at.x, sprite.at.y} + at.linear * Point2{0.5, 0.5} - Point2{0.5, 0.5};
  const cv::Matx23d m(at.linear(0, 0), at.linear(0, 1), t.x(), at.linear(1, 0), at.linear(1, 1), t.y());
  cv::warpAffine(upright, sprite.coverage, m, size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return sprite;
}

detail::Scene place_plate(const Plate& plate, const RenderOptions& o, RenderedPlate& out) {
  const double px_per_m = o.dpi / 0.0254;
  if (!(plate.width_m > 0.0) || !(plate.height_m > 0.0) || !std::isfinite(plate.width_m * plate.height_m)) {
    throw Error(fmt::format("render: the page must have a positive size, got {} × {} mm", plate.width_m * 1e3, plate.height_m * 1e3));
  }
  const cv::Size size = plate_image_size(plate, o);
  const ScannerBed* bed = plate.bed ? &*plate.bed : nullptr;
  out.placement = page_placement(bed);
  out.size_px = size;
  const cv::Size2d image_m(bed ? bed->width_m : plate.width_m, bed ? bed->height_m : plate.height_m);
  detail::Scene scene;
  scene.cols = size.width;
  scene.rows = size.height;
  scene.radius_px = o.mark_width_m * px_per_m / 2;
  const double r = o.mark_width_m / 2;
  double points = 0;
  for (const auto& mark : plate.marks) {
    for (const auto& side : mark.sides) points += static_cast<double>(side.size());
  }
  detail::check_path_points(points, fmt::format("the plate's {} marks", plate.marks.size()));
  const auto stroke_of = [&](const std::vector<std::vector<Point2>>& sides) {
    std::vector<Point2> polyline;
    for (const auto& side : sides) {
      for (const auto& p : side) polyline.push_back(p * px_per_m);
    }
    return polyline;
  };
  for (std::size_t k = 0; k < plate.marks.size(); ++k) {
    const auto& mark = plate.marks[k];
    const std::string name = mark_name(mark, k);
    if (mark.sides.empty()) refuse(mark.where, fmt::format("{} has no path", name));
    on_page(mark.sides, plate, r, name, mark.where);
    PlateMarkTruth truth;
    truth.id = mark.id;
    truth.sides = placed(mark.sides, out.placement, image_m, r, name, mark.where);
    truth.closed = mark.closed;
    truth.truth = evaluation::measure_sides(truth.sides, mark.closed, o.truth_options);
    truth.box_m = box_of(truth.sides);
    scene.strokes_px.push_back(stroke_of(truth.sides));
    out.marks.push_back(std::move(truth));
  }
  for (std::size_t k = 0; k < plate.fiducials.size(); ++k) {
    const auto& f = plate.fiducials[k];
    const std::string name = fmt::format("fiducial {}", k + 1);
    try {
      f.shape.check(name, o.mark_width_m);
    } catch (const Error& e) {
      refuse(f.where, e.message());
    }
    const auto strokes = fiducial_strokes(f);
    on_page(strokes, plate, r, name, f.where);
    for (const auto& stroke : placed(strokes, out.placement, image_m, r, name, f.where)) scene.strokes_px.push_back(stroke_of({stroke}));
    out.fiducials_m.push_back(out.placement.apply(f.at_m));
  }
  const int thickness = std::max(1, static_cast<int>(std::lround(2 * scene.radius_px)));
  for (const auto& label : plate.labels) {
    if (!label.at_m.allFinite() || !(label.height_m > 0.0) || label.height_m > 0.1) {
      refuse(label.where, fmt::format("label '{}' needs a finite position and a height in (0, 100] mm", label.text));
    }
    const detail::Scene::Text text{label.text, label.at_m * px_per_m, label.height_m * px_per_m};
    cv::Point origin;
    const cv::Mat upright = detail::label_coverage(text, thickness, origin);
    // The text's ink spans the canvas less its padding: from the origin up by the height, right by the advance.
    const double right = label.at_m.x() + (upright.cols - 2 * (thickness + 2)) / px_per_m;
    const double top = label.at_m.y() - (origin.y - (thickness + 2)) / px_per_m;
    const double bottom = label.at_m.y() + (upright.rows - origin.y - (thickness + 2)) / px_per_m;
    if (label.at_m.x() < 0 || top < 0 || right > plate.width_m || bottom > plate.height_m) {
      refuse(label.where, fmt::format("label '{}' at x = {:.1f} mm, y = {:.1f} mm (its letters x {:.1f}..{:.1f} mm, y {:.1f}..{:.1f} "
                                      "mm) is not on the {:.1f} × {:.1f} mm page",
                                      label.text, label.at_m.x() * 1e3, label.at_m.y() * 1e3, label.at_m.x() * 1e3, right * 1e3,
                                      top * 1e3, bottom * 1e3, plate.width_m * 1e3, plate.height_m * 1e3));
    }
    if (bed) {
      scene.sprites.push_back(label_sprite(text, thickness, out.placement, px_per_m));
    } else {
      scene.labels.push_back(text);
    }
  }
  if (bed) {
    detail::Sheet sheet;
    sheet.to_page = out.placement.linear.inverse();
    sheet.origin_px = out.placement.offset * px_per_m;
    sheet.width_px = plate.width_m * px_per_m;
    sheet.height_px = plate.height_m * px_per_m;
    sheet.edge_blur_px = std::sqrt(o.blur_px * o.blur_px + 1.0 / 12);
    sheet.bed = *bed;
    sheet.px_per_m = px_per_m;
    cv::RNG rng(o.seed ^ 0x5a5a5a5aULL);  // its own sequence: the noise, texture and specks stay as without smudges
    sheet.smudges = detail::scatter_smudges(sheet, bed->smudges, rng);
    scene.sheet = std::move(sheet);
  }
  return scene;
}

}  // namespace

RenderedPlate render_plate(const Plate& plate, const RenderOptions& o, const RowSink& sink) {
  detail::check_render_options(o);
  RenderedPlate out;
  const detail::Scene scene = place_plate(plate, o, out);
  out.dpi = o.dpi;
  out.mark_width_m = o.mark_width_m;
  detail::rasterise(scene, o, sink);
  return out;
}

RenderedPlate render_plate(const Plate& plate, const RenderOptions& o) {
  detail::check_render_options(o);
  RenderedPlate out;
  const detail::Scene scene = place_plate(plate, o, out);
  out.dpi = o.dpi;
  out.mark_width_m = o.mark_width_m;
  out.image = detail::rasterise_image(scene, o);
  return out;
}

}  // namespace stiffpath::vision
