// Chains of short G64 chords refitted as tangent biarcs within P, so the curvature follows the cut curve.
#include "stiffpath/motion/chord_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

#include "stiffpath/motion/biarc.hpp"
#include "stiffpath/motion/junction.hpp"

namespace stiffpath::motion {

namespace {

constexpr double max_turn_rad = 0.25 * std::numbers::pi;
constexpr double max_length_ratio = 4.0;
constexpr double min_chord_m = 1e-6;
constexpr int checks_per_piece = 8;  // a piece is checked at 9 evenly spaced points
// No piece shorter than this (0.1 µm): the planner's junction rules assume segments of some length,
// and a sliver of line between two arcs would add a junction for nothing.
constexpr double min_piece_m = 1e-7;

double cross(const Vec2& a, const Vec2& b) noexcept { return a.x() * b.y() - a.y() * b.x(); }

bool is_chord(const PathSegment& s) noexcept {
  return s.kind == SegmentKind::line && !s.rapid && s.length_m >= min_chord_m;
}

// Whether b continues the chain that ends with a (see the class comment).
bool continues(const PathSegment& a, const PathSegment& b) noexcept {
  if (!is_chord(a) || !is_chord(b) || a.mode != JunctionMode::blend || !(a.blend_tolerance_m > 0.0) ||
      a.laser_on != b.laser_on || a.end_m != b.start_m) {
    return false;
  }
  if (std::max(a.length_m, b.length_m) > max_length_ratio * std::min(a.length_m, b.length_m)) return false;
  const Vec2 in = (a.end_m - a.start_m) / a.length_m, out = (b.end_m - b.start_m) / b.length_m;
  return turn_angle_rad(in, out) <= max_turn_rad;
}

// The curve through the chords near vertex i: y = c0 + c1·x + c2·x² (+ c3·x³) in the frame at v_i whose x axis
// runs from v_{i−1} to v_{i+1}, fitted by least squares to v_{i−w} … v_{i+w}. w = 1 interpolates the
// three points (the circle through them to second order); wider stencils average the coordinates'
// rounding (0.1 µm on 0.1 mm chords turns a chord by 1 mrad, a curvature error of tens of 1/m).
// w grows up to 3 while the fit stays within P/20 of every stencil point (a cubic describes
// them up to their rounding), so corners and fast changes of curvature keep the narrow stencil.
struct LocalFit {
  Vec2 point_m = Vec2::Zero();
  Vec2 tangent = Vec2::UnitX();
  double curvature_1_m = 0.0;
  double residual_m = 0.0;  // the largest distance of a stencil point from the parabola
};

std::optional<LocalFit> fit_stencil(const std::vector<Vec2>& v, std::size_t i, std::size_t w) {
  const Vec2 axis = (v[i + 1] - v[i - 1]).normalized(), normal = left_normal(axis);
  double scale = 0.0;
  for (std::size_t j = i - w; j <= i + w; ++j) scale = std::max(scale, std::abs((v[j] - v[i]).dot(axis)));
  // Three points: the parabola through them; more: a cubic, whose x³ term takes up the change of
  // curvature that would otherwise tilt the fitted tangent (by κ′/6·Σx⁴/Σx² on a parabola).
  const int terms = w == 1 ? 3 : 4;
  Eigen::Matrix4d normal_matrix = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  double previous_x = -INFINITY;
  std::array<Eigen::Vector4d, 7> rows;
  std::array<double, 7> ys{};
  for (std::size_t j = i - w; j <= i + w; ++j) {
    const Vec2 d = v[j] - v[i];
    const double x = d.dot(axis) / scale, y = d.dot(normal);
    if (!(x > previous_x)) return std::nullopt;  // the stencil must run forward along the axis
    previous_x = x;
    const std::size_t r = j - (i - w);
    rows[r] = Eigen::Vector4d(1.0, x, x * x, terms == 4 ? x * x * x : 0.0);
    ys[r] = y;
    normal_matrix += rows[r] * rows[r].transpose();
    rhs += y * rows[r];
  }
  Eigen::Vector4d c = Eigen::Vector4d::Zero();
  c.head(terms) = normal_matrix.topLeftCorner(terms, terms).ldlt().solve(rhs.head(terms));
  if (!c.allFinite()) return std::nullopt;
  double residual = 0.0;
  for (std::size_t r = 0; r <= 2 * w; ++r) residual = std::max(residual, std::abs(rows[r].dot(c) - ys[r]));
  const double slope = c[1] / scale, bend = c[2] / (scale * scale);
  LocalFit fit;
  fit.point_m = v[i] + c[0] * normal;
  fit.tangent = (axis + slope * normal).normalized();
  fit.curvature_1_m = 2.0 * bend / std::pow(1.0 + slope * slope, 1.5);
  fit.residual_m = residual;
  return fit;
}

LocalFit fit_around(const std::vector<Vec2>& v, std::size_t i, double tolerance_m) {
  LocalFit best;  // three points always run forward within a chain (turns ≤ 45°); the rest is a guard
  best.point_m = v[i];
  best.tangent = (v[i + 1] - v[i - 1]).normalized();
  if (const std::optional<LocalFit> narrow = fit_stencil(v, i, 1)) best = *narrow;
  const std::size_t n = v.size() - 1;
  for (std::size_t w = 2; w <= 3 && w <= i && i + w <= n; ++w) {
    const std::optional<LocalFit> wider = fit_stencil(v, i, w);
    if (!wider || wider->residual_m > 0.05 * tolerance_m) break;
    best = *wider;
  }
  return best;
}

// The arc that leaves the chord from `start_m` (unit direction u) tangentially and reaches q with the
// tangent t: its chord to q makes half the angle β from u to t with u, so it starts h/tan(β/2) before
// q's foot on the chord (h: q's distance from it); on a circle that is the arc of the circle's own
// curvature, where a biarc from the chord's midpoint would put twice it into one half. nullopt
// unless that start lies on the chord ahead of start_m.
std::optional<PathSegment> entry_arc(const Vec2& start_m, const Vec2& u, const Vec2& q, const Vec2& t) noexcept {
  const double beta = std::atan2(cross(u, t), u.dot(t)), h = cross(u, q - start_m);
  if (!(std::abs(beta) > 1e-9) || !(h * beta > 0.0)) return std::nullopt;
  const double foot = (q - start_m).dot(u), along = foot - h / std::tan(0.5 * beta);
  if (!(along >= min_piece_m) || !(foot - along >= min_piece_m)) return std::nullopt;
  return arc_from_tangent(start_m + along * u, u, q);
}

}  // namespace

ChordFitter::ChordFitter(PathSource& source, bool merged_only) : source_(source), merged_only_(merged_only) {}

std::optional<PathSegment> ChordFitter::next() {
  while (ready_.empty()) {
    if (exhausted_) {
      if (chain_.empty()) return std::nullopt;
      fit_chain(false);
      chain_.clear();
      chain_starts_mid_ = false;
      continue;
    }
    std::optional<PathSegment> incoming = source_.next();
    if (!incoming) {
      exhausted_ = true;
      continue;
    }
    const bool candidate = !merged_only_ || incoming->merged;  // ChordFitting::merged: merged lines only
    if (!chain_.empty() && candidate && (!merged_only_ || chain_.back().merged) && continues(chain_.back(), *incoming)) {
      chain_.push_back(*incoming);
      if (chain_.size() >= max_fitted_chain) {  // fit up to the last chord's midpoint, go on from there
        fit_chain(true);
        const PathSegment last = chain_.back();
        chain_.assign(1, last);
        chain_starts_mid_ = true;
      }
      continue;
    }
    if (chain_.size() == 1 && !chain_starts_mid_) {  // a chain of one chord: nothing to fit
      ready_.push_back(chain_.front());
      chain_.clear();
    } else if (!chain_.empty()) {
      fit_chain(false);
      chain_.clear();
      chain_starts_mid_ = false;
    }
    if (candidate && is_chord(*incoming)) {
      chain_.push_back(*incoming);
    } else {
      ready_.push_back(*incoming);
    }
  }
  PathSegment out = ready_.front();
  ready_.pop_front();
  return out;
}

void ChordFitter::fit_chain(bool ends_mid) {
  const std::size_t n = chain_.size();
  std::vector<Vec2> v(n + 1), u(n), mid(n);
  std::vector<double> length(n);
  for (std::size_t k = 0; k < n; ++k) {
    v[k] = chain_[k].start_m;
    length[k] = chain_[k].length_m;
    u[k] = (chain_[k].end_m - chain_[k].start_m) / length[k];
    mid[k] = 0.5 * (chain_[k].start_m + chain_[k].end_m);
  }
  v[n] = chain_[n - 1].end_m;

  // Inner vertices 1 … n−1: a local parabola fitted to the vertex and up to 3 neighbours on each side
  // gives the curve's point, tangent and curvature there.
  std::vector<double> curvature(n + 1, 0.0);
  std::vector<Vec2> tangent(n + 1, Vec2::UnitX()), through(v);
  std::vector<char> smooth(n + 1, 0);
  for (std::size_t i = 1; i < n; ++i) {
    const LocalFit fit = fit_around(v, i, chain_[i - 1].blend_tolerance_m);
    curvature[i] = fit.curvature_1_m;
    tangent[i] = fit.tangent;
    through[i] = fit.point_m;
  }
  // The chords about v_i cut off s = |κ_i|·L²/8 of the curve; the fitted curve runs s/2 inside the
  // vertex (κ from v_i's own fit, so a corner next door does not push its neighbours inwards).
  auto vertex_tolerance = [&](std::size_t i) { return chain_[i - 1].blend_tolerance_m; };
  for (std::size_t i = 1; i < n; ++i) {
    const double tolerance = vertex_tolerance(i), kappa = std::abs(curvature[i]);
    const double longest = std::max(length[i - 1], length[i]);
    if (kappa * longest * longest / 8.0 > 2.0 * tolerance) continue;  // too coarse for P: a corner
    smooth[i] = 1;
    const double mean_square = 0.5 * (length[i - 1] * length[i - 1] + length[i] * length[i]);
    const double inwards = std::min(tolerance, kappa * mean_square / 16.0);
    if (curvature[i] != 0.0) through[i] += std::copysign(inwards, curvature[i]) * left_normal(tangent[i]);
  }

  // The pieces of chord k, from its start state (q_k on the curve, or the chord) to its end state.
  auto build = [&](std::size_t k, std::vector<PathSegment>& out) {
    out.clear();
    const bool from_curve = k >= 1 && smooth[k], to_curve = k + 1 < n && smooth[k + 1];
    const bool start_mid = k == 0 && chain_starts_mid_, end_mid = k + 1 == n && ends_mid;
    double tolerance = std::numeric_limits<double>::infinity();
    if (from_curve) tolerance = std::min(tolerance, vertex_tolerance(k));
    if (to_curve) tolerance = std::min(tolerance, vertex_tolerance(k + 1));
    auto within = [&](const PathSegment& piece) {
      for (int m = 0; m <= checks_per_piece; ++m) {
        const Vec2 p = point_at(piece, piece.length_m * m / checks_per_piece).position_m;
        if (!(distance_to_segment_m(p, v[k], v[k + 1]) <= tolerance * (1.0 + 1e-9))) return false;
      }
      return true;
    };
    auto add_line = [&](const Vec2& a, const Vec2& b) {
      if (b != a) out.push_back(carrying_attributes(make_line(a, b), chain_[k]));
    };
    auto add_biarc = [&](const Vec2& p0, const Vec2& t0, const Vec2& p1, const Vec2& t1) {
      const auto pieces = biarc(p0, t0, p1, t1);
      if (!pieces || (*pieces)[0].length_m < min_piece_m || (*pieces)[1].length_m < min_piece_m) return false;
      for (const PathSegment& piece : *pieces) {
        if (!within(piece)) return false;
      }
      if ((*pieces)[0].kind == SegmentKind::line && (*pieces)[1].kind == SegmentKind::line) {
        add_line(p0, p1);
      } else {
        for (const PathSegment& piece : *pieces) out.push_back(carrying_attributes(piece, chain_[k]));
      }
      return true;
    };
    if (!from_curve && !to_curve) {
      add_line(start_mid ? mid[k] : v[k], end_mid ? mid[k] : v[k + 1]);
      return true;
    }
    if (from_curve && to_curve) return add_biarc(through[k], tangent[k], through[k + 1], tangent[k + 1]);
    if (from_curve) {  // leaving the curve onto the rest of the chord
      if (!end_mid) {
        if (const auto arc = entry_arc(v[k + 1], -u[k], through[k], -tangent[k])) {  // found backwards
          const PathSegment forward = make_arc(through[k], arc->start_m, arc->center_m, -arc->sweep_rad);
          if (arc->kind == SegmentKind::arc && within(forward)) {
            out.push_back(carrying_attributes(forward, chain_[k]));
            add_line(forward.end_m, v[k + 1]);
            return true;
          }
        }
      }
      if (!add_biarc(through[k], tangent[k], mid[k], u[k])) return false;
      if (!end_mid) add_line(mid[k], v[k + 1]);
      return true;
    }
    if (!start_mid) {  // joining the curve from the chord
      if (const auto arc = entry_arc(v[k], u[k], through[k + 1], tangent[k + 1])) {
        if (arc->kind == SegmentKind::arc && within(*arc)) {
          add_line(v[k], arc->start_m);
          out.push_back(carrying_attributes(*arc, chain_[k]));
          return true;
        }
      }
      add_line(v[k], mid[k]);
    }
    return add_biarc(mid[k], u[k], through[k + 1], tangent[k + 1]);
  };

  // Where a chord's pieces leave its tolerance, both its vertices become corners; the chord before
  // then ends at the vertex instead of on the curve and is fitted again.
  std::vector<std::vector<PathSegment>> pieces(n);
  std::size_t k = 0;
  while (k < n) {
    if (build(k, pieces[k])) {
      ++k;
      continue;
    }
    const bool refit_before = k >= 1 && smooth[k];
    if (k >= 1) smooth[k] = 0;
    if (k + 1 < n) smooth[k + 1] = 0;
    if (refit_before) --k;
  }
  for (std::size_t c = 0; c < n; ++c) {
    // The chord's mode says how its end is passed; the joints inside it are tangent.
    for (PathSegment& piece : pieces[c]) piece.mode = JunctionMode::blend;
    if (!pieces[c].empty()) pieces[c].back().mode = chain_[c].mode;
    for (PathSegment& piece : pieces[c]) ready_.push_back(piece);
  }
}

}  // namespace stiffpath::motion
