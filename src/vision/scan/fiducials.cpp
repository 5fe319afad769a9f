// Fiducials on a plate's scan: the dark features of a ring's size, each checked as a ring (and cross), its centre from a circle fit.
#include "stiffpath/vision/scan/fiducials.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "ring_fit.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::vision {

void FiducialShape::check(const std::string& what, double mark_width_m) const {
  if (!(ring_radius_m >= 0.5e-3) || !(ring_radius_m <= 50e-3)) {
    throw Error(fmt::format("{}: the ring's radius must be 0.5 to 50 mm, got {} mm", what, ring_radius_m * 1e3));
  }
  if (cross && (!(cross_arm_m > 0) || !(cross_arm_m + 2 * mark_width_m <= ring_radius_m))) {
    throw Error(fmt::format("{}: the cross's arms ({} mm) must stop a mark's width short of the ring: at most the radius less two "
                            "widths, {:.3f} mm", what, cross_arm_m * 1e3, (ring_radius_m - 2 * mark_width_m) * 1e3));
  }
}

namespace {

// One dark feature of about a ring's size, and what became of it.
struct Candidate {
  Point2 at_px{0, 0};  // the feature's box centre (whole image px)
  std::string reason;  // why it is not a fiducial, empty when it is one
  Fiducial found;
};

std::string where_text(const Point2& px, double px_per_m) {
  return fmt::format("x = {:.2f} mm, y = {:.2f} mm", px.x() / px_per_m * 1e3, px.y() / px_per_m * 1e3);
}

// Checks a feature as a ring of the shape (and its cross), returning the fiducial or the reason it is none.
Candidate examine(const cv::Mat& view, const detail::CoarseGrid& grid, const cv::Rect& box_px, const Point2& origin,
                  const FiducialSearch& search, double px_per_m) {
  Candidate c;
  const Point2 guess{box_px.x + box_px.width / 2.0, box_px.y + box_px.height / 2.0};
  c.at_px = guess + origin;
  const double radius = search.shape.ring_radius_m * px_per_m;
  const detail::RingFit ring = detail::fit_ring(view, grid, guess, radius, search.radius_tolerance * radius + 2.0 * grid.cell + 4.0);
  const auto mm = [&](double px) { return px / px_per_m * 1e3; };
  if (!ring.ok) {
    c.reason = "no ring: too little darkness along a circle of the fiducial's radius";
    return c;
  }
  c.at_px = ring.centre + origin;
  if (ring.covered < 0.97) {
    c.reason = fmt::format("the ring is broken: it is missing on {:.0f}° of its circle", 360 * (1 - ring.covered));
    return c;
  }
  if (std::abs(ring.radius - radius) > search.radius_tolerance * radius) {
    c.reason = fmt::format("a ring of radius {:.3f} mm, not {:.3f} mm", mm(ring.radius), mm(radius));
    return c;
  }
  if (ring.rms > std::max(1.0, 0.25 * ring.width)) {
    c.reason = fmt::format("not round: its centre line strays {:.3f} mm (rms) from a circle", mm(ring.rms));
    return c;
  }
  // The centre: the cross's crossing (dark) or paper, as the shape says.
  const double centre_darkness = detail::darkness_at(view, grid, ring.centre);
  const bool dark_centre = centre_darkness > 0.5 * ring.darkness;
  if (search.shape.cross != dark_centre) {
    c.reason = search.shape.cross ? "a ring without the cross at its centre" : "a ring with something dark at its centre";
    return c;
  }
  c.found.centre_m = (ring.centre + origin) / px_per_m;
  c.found.radius_m = ring.radius / px_per_m;
  c.found.rms_m = ring.rms / px_per_m;
  c.found.width_m = ring.width / px_per_m;
  c.found.cross = dark_centre;
  // Points around a circle fix its centre to rms·√(2/N); neighbouring points share the blur, the paper's
  // texture and the noise of the pixels between them, so N counts one point per 16 px of the circumference
  // at most (on rendered plates the errors are then 0.1 to 2 of these uncertainties).
  const double independent = std::min(static_cast<double>(ring.points), 2 * std::numbers::pi * ring.radius / 16.0);
  c.found.uncertainty_m = ring.rms * std::sqrt(2.0 / std::max(independent, 1.0)) / px_per_m;
  return c;
}

}  // namespace

std::vector<Fiducial> find_fiducials(const cv::Mat& grey, double dpi, const FiducialSearch& search) {
  ScanOptions options;
  options.label = search.label;
  options.roi_px = search.roi_px;
  options.sides = 1;
  detail::check_scan_input(grey, dpi, options);
  const SourceLocation where{search.label, 0, 0};
  if (search.expected < 0 || search.expected > 1000) throw Error(where, fmt::format("expected fiducials must be 0..1000, got {}", search.expected));
  if (!(search.radius_tolerance > 0) || !(search.radius_tolerance < 0.5)) {
    throw Error(where, fmt::format("the radius tolerance must be in (0, 0.5), got {}", search.radius_tolerance));
  }
  search.shape.check("fiducial shape", 0.0);
  const double px_per_m = dpi / 0.0254;
  const cv::Mat view = search.roi_px.empty() ? grey : grey(search.roi_px);
  const Point2 origin{search.roi_px.x, search.roi_px.y};
  const detail::CoarseGrid grid = detail::build_coarse_grid(view, options.tuning);
  const detail::Features features = detail::find_features(grid);
  // Features about a ring's size (its outer diameter, give or take the tolerance and the mark's width).
  const double diameter = 2 * search.shape.ring_radius_m * px_per_m;
  std::vector<Candidate> candidates;
  for (const auto& f : features.list) {
    const cv::Rect box(f.box.x * grid.cell, f.box.y * grid.cell, f.box.width * grid.cell, f.box.height * grid.cell);
    const double size = std::max(box.width, box.height), across = std::min(box.width, box.height);
    const double smallest = (1 - search.radius_tolerance) * diameter - 2.0 * grid.cell, largest = 1.5 * diameter;
    if (size < smallest || size > largest || across < 0.8 * size) continue;  // not a ring's shape or size (a cross inside is smaller)
    Candidate c = examine(view, grid, box, origin, search, px_per_m);
    if (!f.border.empty() && c.reason.empty()) c.reason = fmt::format("it touches the {} border of the image", f.border);
    candidates.push_back(std::move(c));
  }
  std::vector<Fiducial> found;
  std::string rejected;
  for (const auto& c : candidates) {
    if (c.reason.empty()) {
      found.push_back(c.found);
    } else {
      rejected += fmt::format("; near {}: {}", where_text(c.at_px, px_per_m), c.reason);
    }
  }
  std::sort(found.begin(), found.end(), [](const Fiducial& a, const Fiducial& b) {
    return a.centre_m.y() != b.centre_m.y() ? a.centre_m.y() < b.centre_m.y() : a.centre_m.x() < b.centre_m.x();
  });
  const std::string shape = fmt::format("rings of radius {} mm{}", search.shape.ring_radius_m * 1e3, search.shape.cross ? " with a cross" : "");
  const auto listed = [&] {
    std::string out;
    for (const auto& f : found) out += fmt::format("{}({:.2f}, {:.2f}) mm", out.empty() ? "" : ", ", f.centre_m.x() * 1e3, f.centre_m.y() * 1e3);
    return out;
  };
  if (found.empty() || (search.expected > 0 && static_cast<int>(found.size()) < search.expected)) {
    throw Error(where, fmt::format("fiducials missing: found {}{} of the {} {} expected{}{}", found.size(),
                                   found.empty() ? "" : " (" + listed() + ")", search.expected > 0 ? std::to_string(search.expected) : "at least 1",
                                   shape, candidates.size() > found.size() ? "; candidates rejected" : "", rejected));
  }
  if (search.expected > 0 && static_cast<int>(found.size()) > search.expected) {
    throw Error(where, fmt::format("fiducials ambiguous: found {} {} where {} expected, at {}: which are the plate's cannot be told",
                                   found.size(), shape, search.expected, listed()));
  }
  for (std::size_t i = 0; i < found.size(); ++i) {
    for (std::size_t j = i + 1; j < found.size(); ++j) {
      if ((found[i].centre_m - found[j].centre_m).norm() < 2 * search.shape.ring_radius_m) {
        throw Error(where, fmt::format("fiducials ambiguous: two rings overlap, at {}", listed()));
      }
    }
  }
  return found;
}

}  // namespace stiffpath::vision
