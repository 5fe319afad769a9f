// The scan-to-robot transform of a calibration plate: fiducials matched under every rigid assignment, fitted by least squares.
#include "plate_registration.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numeric>

#include "scan_internal.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/vision/scan/fiducials.hpp"

namespace stiffpath::vision {

Eigen::Vector2d PlateRegistration::to_robot(const Eigen::Vector2d& scan_m) const { return linear * scan_m + translation_m; }

Eigen::Vector2d PlateRegistration::to_scan(const Eigen::Vector2d& robot_m) const {
  // linear is orthogonal: its inverse is its transpose.
  return linear.transpose() * (robot_m - translation_m);
}

namespace detail {

namespace {

// Least-squares rotation (times the mirror diag(1, −1) when `mirror`) and translation taking scan points
// `s` onto robot points `r` (2-D Kabsch: the angle is the atan2 of the summed cross and dot products).
PlateRegistration fit_rigid(const std::vector<Point2>& s, const std::vector<Point2>& r, bool mirror) {
  const Eigen::Matrix2d flip = mirror ? Eigen::Vector2d(1, -1).asDiagonal().toDenseMatrix() : Eigen::Matrix2d::Identity();
  Point2 sc = Point2::Zero(), rc = Point2::Zero();
  for (std::size_t i = 0; i < s.size(); ++i) sc += flip * s[i], rc += r[i];
  sc /= static_cast<double>(s.size());
  rc /= static_cast<double>(s.size());
  double cross = 0, dot = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Point2 a = flip * s[i] - sc, b = r[i] - rc;
    cross += a.x() * b.y() - a.y() * b.x();
    dot += a.dot(b);
  }
  const double angle = std::atan2(cross, dot);
  Eigen::Matrix2d rot;
  rot << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  PlateRegistration reg;
  reg.linear = rot * flip;
  reg.translation_m = rc - rot * sc;
  reg.mirrored = reg.linear.determinant() > 0;  // the image's y runs down, the robot's up: a faithful scan has det −1
  reg.fiducials = static_cast<int>(s.size());
  double sum2 = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double e = (reg.to_robot(s[i]) - r[i]).norm();
    sum2 += e * e;
    reg.residual_max_m = std::max(reg.residual_max_m, e);
  }
  reg.residual_rms_m = std::sqrt(sum2 / static_cast<double>(s.size()));
  return reg;
}

struct Candidate {
  PlateRegistration reg;
  std::vector<std::size_t> assignment;  // plate fiducial of each found one
  double ink = 0;
};

std::string assignment_text(const calibration::PlateDesign& plate, const Candidate& c) {
  std::string out;
  for (std::size_t i = 0; i < c.assignment.size(); ++i) {
    out += fmt::format("{}{}", i ? ", " : "", plate.fiducials[c.assignment[i]].id);
  }
  return fmt::format("[{}]{}", out, c.reg.mirrored ? " mirrored" : "");
}

}  // namespace

double stroke_ink(const calibration::PlateDesign& plate, const cv::Mat& grey, double px_per_m,
                  const PlateRegistration& registration, double corridor_half_width_m) {
  constexpr double kStep_m = 0.5e-3, kDark = 0.25;
  const double reach_px = corridor_half_width_m * px_per_m;
  int samples = 0, hits = 0;
  for (const auto& stroke : plate.strokes) {
    const auto poly = stroke.polyline_m();
    for (std::size_t k = 0; k + 1 < poly.size(); ++k) {
      const Point2 d = poly[k + 1] - poly[k];
      const double len = d.norm();
      if (len <= 0) continue;
      const Point2 across = registration.linear.transpose() * Point2(-d.y(), d.x()) / len;  // unit, on the scan
      const int n = std::max(1, static_cast<int>(len / kStep_m));
      for (int j = 0; j < n; ++j) {
        const Point2 c = registration.to_scan(poly[k] + d * ((j + 0.5) / n)) * px_per_m;
        ++samples;
        double lo = 1e30, hi = 0;
        bool inside = true;
        for (double t = -reach_px; t <= reach_px && inside; t += 1.0) {
          const Point2 p = c + t * across;
          const int col = static_cast<int>(std::floor(p.x())), row = static_cast<int>(std::floor(p.y()));
          if (col < 0 || row < 0 || col >= grey.cols || row >= grey.rows) {
            inside = false;
            break;
          }
          const double v = pixel(grey, row, col);
          lo = std::min(lo, v), hi = std::max(hi, v);
        }
        if (inside && hi > 0 && 1.0 - lo / hi > kDark) ++hits;
      }
    }
  }
  return samples ? static_cast<double>(hits) / samples : 0.0;
}

PlateRegistration register_plate(const calibration::PlateDesign& plate, const cv::Mat& grey, double dpi,
                                 const std::string& label, const PlateScanOptions& options) {
  const std::size_t n = plate.fiducials.size();
  if (n < 3 || n > kMaxPlateFiducials) {
    throw Error(fmt::format("{}: the plate has {} fiducials; registering a scan needs 3 … {}", label, n, kMaxPlateFiducials));
  }
  const auto& first = plate.fiducials.front();
  for (const auto& f : plate.fiducials) {
    if (std::abs(f.ring_radius_m - first.ring_radius_m) > 1e-9 || std::abs(f.cross_arm_m - first.cross_arm_m) > 1e-9) {
      throw Error(fmt::format("{}: the plate's fiducials {} and {} differ in shape; the scan looks for one shape", label,
                              first.id, f.id));
    }
  }
  FiducialSearch search;
  search.shape = {first.ring_radius_m, true, first.cross_arm_m};
  search.expected = static_cast<int>(n);
  search.label = label;
  const std::vector<Fiducial> found = find_fiducials(grey, dpi, search);  // throws for a missing or extra one
  std::vector<Point2> scan_m, robot_m(n);
  for (const auto& f : found) scan_m.push_back(f.centre_m);

  // Every assignment, with and without the mirror; keep those within the residual limit.
  std::vector<std::size_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::vector<Candidate> fits;
  double best_rms = 1e30;
  do {
    for (std::size_t i = 0; i < n; ++i) robot_m[i] = plate.fiducials[perm[i]].centre_m;
    for (const bool mirror : {false, true}) {
      Candidate c{fit_rigid(scan_m, robot_m, mirror), perm};
      best_rms = std::min(best_rms, c.reg.residual_rms_m);
      if (c.reg.residual_rms_m <= options.max_residual_m) fits.push_back(std::move(c));
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  if (fits.empty()) {
    throw Error(fmt::format("{}: the {} fiducials found do not fit the plate's by any rigid motion: the best fit leaves "
                            "{:.1f} um rms, more than the {:.1f} um allowed (a distorted scan, a scale other than the "
                            "resolution says, or another plate)",
                            label, n, best_rms * 1e6, options.max_residual_m * 1e6));
  }
  if (fits.size() > 1) {
    // A symmetric layout (four corners of a rectangle) fits several ways: the strokes tell them apart.
    const double px_per_m = dpi / 0.0254;
    for (auto& c : fits) c.ink = stroke_ink(plate, grey, px_per_m, c.reg, options.corridor_half_width_m);
    std::sort(fits.begin(), fits.end(), [](const Candidate& a, const Candidate& b) { return a.ink > b.ink; });
    if (fits[0].ink - fits[1].ink < options.min_ink_margin) {
      throw Error(fmt::format("{}: the fiducials match the plate's in {} ways within {:.1f} um, and the strokes do not "
                              "tell them apart: {} has ink along {:.0f} % of the strokes, {} along {:.0f} % (ambiguous)",
                              label, fits.size(), options.max_residual_m * 1e6, assignment_text(plate, fits[0]),
                              100 * fits[0].ink, assignment_text(plate, fits[1]), 100 * fits[1].ink));
    }
  }
  return fits.front().reg;
}

}  // namespace detail

}  // namespace stiffpath::vision
