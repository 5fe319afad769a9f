// identify(): least squares of the predicted marks against the measured ones, with what the plate cannot tell held.
#include "stiffpath/calibration/identify.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::calibration {

namespace {

// The parameters in the fit's order, with their typical sizes (the solver's scale) and bounds.
struct ParameterSpec {
  const char* name;
  double scale, lower, upper;
};
constexpr ParameterSpec kParameters[] = {
    {"sx0", 0.05, 0.3, 3.0},  {"sx1", 0.05, -1.0, 1.0},      {"sx2", 0.05, -1.0, 1.0},
    {"sy0", 0.05, 0.3, 3.0},  {"sy1", 0.05, -1.0, 1.0},      {"sy2", 0.05, -1.0, 1.0},
    {"sxy0", 0.02, -0.5, 0.5}, {"sxy1", 0.02, -0.5, 0.5},    {"sxy2", 0.02, -0.5, 0.5},
    {"damping_ratio", 0.02, 0.002, 0.6}, {"frequency_scale", 0.05, 0.3, 3.0},
    {"laser_on_delay_s", 2e-4, -0.02, 0.02}, {"laser_off_delay_s", 2e-4, -0.02, 0.02},
};
constexpr int kCount = static_cast<int>(std::size(kParameters));

Eigen::VectorXd to_vector(const TipParameters& t) {
  Eigen::VectorXd x(kCount);
  x << t.correction.sx[0], t.correction.sx[1], t.correction.sx[2], t.correction.sy[0], t.correction.sy[1],
      t.correction.sy[2], t.correction.sxy[0], t.correction.sxy[1], t.correction.sxy[2], t.damping_ratio, t.frequency_scale, t.laser_on_delay_s, t.laser_off_delay_s;
  return x;
}

TipParameters from_vector(const Eigen::VectorXd& x, TipParameters t) {
  t.correction.sx = {x[0], x[1], x[2]};
  t.correction.sy = {x[3], x[4], x[5]};
  t.correction.sxy = {x[6], x[7], x[8]};
  t.damping_ratio = x[9];
  t.frequency_scale = x[10];
  t.laser_on_delay_s = x[11];
  t.laser_off_delay_s = x[12];
  return t;
}

// One measured mark as the fit uses it: its points (thinned), the stroke's direction and where its end points.
struct MarkData {
  std::string id;
  std::size_t pulse = 0;
  std::vector<Vec2> points;
  std::vector<double> s;  // arc length of each point along the measured mark
  Vec2 start_direction, end_direction;
  bool ends = true;  // whether its two ends are measured (an arc's centre line is measured short of them)
};

// Signed normal distances of `points` to the polyline `path` (positive to the path's left), searching forward
// from the last match within a window of the path, so that a wavy tail is matched wave by wave.
std::vector<double> normal_distances(const std::vector<Vec2>& points, const std::vector<Vec2>& path) {
  std::vector<double> out(points.size(), 0.0);
  if (path.size() < 2) {
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = path.empty() ? 1.0 : (points[i] - path.front()).norm();
    return out;
  }
  std::size_t j = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2& p = points[i];
    double best = std::numeric_limits<double>::infinity(), signed_best = 0.0;
    std::size_t best_j = j;
    double travelled = 0.0;
    for (std::size_t k = j; k + 1 < path.size(); ++k) {
      const Vec2 a = path[k], d = path[k + 1] - path[k];
      const double len2 = d.squaredNorm();
      const double f = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
      const Vec2 off = p - (a + f * d);
      const double dist = off.norm();
      if (dist < best) {
        best = dist, best_j = k;
        const double cross = d.x() * (p - a).y() - d.y() * (p - a).x();
        signed_best = len2 > 0.0 ? (cross >= 0.0 ? dist : -dist) : dist;
      }
      travelled += std::sqrt(len2);
      if (travelled > 2e-3 && best < std::numeric_limits<double>::infinity() && k > best_j + 4) break;
    }
    out[i] = signed_best;
    j = best_j;
  }
  return out;
}

std::vector<MarkData> mark_data(const PlateDesign& plate, const std::vector<ObservedMark>& observed,
                                const std::vector<PredictedMark>& pulses, double spacing) {
  std::map<std::string, const StrokeMark*> strokes;
  for (const auto& m : plate.strokes) strokes[m.id] = &m;
  std::vector<MarkData> out;
  for (const auto& o : observed) {
    const auto it = strokes.find(o.id);
    if (it == strokes.end()) throw Error(fmt::format("calibration: measured mark '{}' is not on the plate", o.id));
    if (o.points_m.size() < 4) throw Error(fmt::format("calibration: mark '{}' has fewer than four measured points", o.id));
    const StrokeMark& plan = *it->second;
    MarkData d;
    d.id = o.id;
    // The laser pulse that made it: the one whose command switched the laser on at the stroke's start.
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pulses.size(); ++i) {
      const double dist = (pulses[i].commanded_start_m - plan.start_m).norm();
      if (dist < nearest) nearest = dist, d.pulse = i;
    }
    if (!(nearest < 0.5e-3)) {
      throw Error(fmt::format("calibration: no laser pulse of the joint file starts at mark {}'s start ({:.3f}, {:.3f}) mm "
                              "(nearest {:.3f} mm away): is it the plate's joint file?",
                              o.id, units::m_to_mm(plan.start_m.x()), units::m_to_mm(plan.start_m.y()), units::m_to_mm(nearest)));
    }
    double s = 0.0, last = -1.0;
    for (std::size_t k = 0; k < o.points_m.size(); ++k) {
      if (k > 0) s += (o.points_m[k] - o.points_m[k - 1]).norm();
      if (k == 0 || k + 1 == o.points_m.size() || s - last >= spacing) {
        d.points.push_back(o.points_m[k]);
        d.s.push_back(s);
        last = s;
      }
    }
    d.start_direction = plan.start_direction();
    d.end_direction = plan.end_direction();
    d.ends = plan.kind != StrokeKind::arc;
    out.push_back(std::move(d));
  }
  if (out.empty()) throw Error("calibration: no measured mark to fit");
  return out;
}

// Every residual: normal distances over σ_point, then the two ends along the mark over σ_end, mark by mark.
Eigen::VectorXd residuals(const std::vector<MarkData>& data, const std::vector<PredictedMark>& predicted,
                          const IdentifyOptions& o) {
  std::size_t n = 0;
  for (const auto& d : data) n += d.points.size() + 2;
  Eigen::VectorXd r(static_cast<Eigen::Index>(n));
  Eigen::Index i = 0;
  for (const auto& d : data) {
    const auto& path = predicted[d.pulse].points_m;
    for (const double dist : normal_distances(d.points, path)) r[i++] = dist / o.point_sigma_m;
    const Vec2 first = path.empty() ? d.points.front() + Vec2(1.0, 0.0) : path.front();
    const Vec2 last = path.empty() ? d.points.back() + Vec2(1.0, 0.0) : path.back();
    r[i++] = d.ends ? (d.points.front() - first).dot(d.start_direction) / o.end_sigma_m : 0.0;
    r[i++] = d.ends ? (d.points.back() - last).dot(d.end_direction) / o.end_sigma_m : 0.0;
  }
  return r;
}

}  // namespace

Identification identify(const std::vector<compensation::JointCommand>& commands, const kinematics::Robot& robot,
                        const compliance::Model& model, const PlateDesign& plate,
                        const std::vector<ObservedMark>& observed, const IdentifyOptions& options) {
  if (!(options.point_sigma_m > 0.0 && options.end_sigma_m > 0.0 && options.point_spacing_m >= 0.0)) {
    throw Error("calibration: the uncertainties must be positive");
  }
  Identification out;
  out.before.damping_ratio = robot.tip_damping_ratio;
  out.before.frequency_scale = robot.tip_frequency_scale;
  out.before.laser_on_delay_s = robot.laser_on_delay_s;
  out.before.laser_off_delay_s = robot.laser_off_delay_s;
  const compliance::GridBounds area = plate.area;
  out.before.correction.origin_m = {0.5 * (area.x_min + area.x_max), 0.5 * (area.y_min + area.y_max)};
  out.before.correction.half_size_m = {0.5 * (area.x_max - area.x_min), 0.5 * (area.y_max - area.y_min)};

  const auto predict = [&](const TipParameters& t) { return predict_marks(commands, robot, model, t, options.response); };
  const std::vector<MarkData> data = mark_data(plate, observed, predict(out.before), options.point_spacing_m);
  const TipParameters base = out.before;
  core::LeastSquaresProblem problem;
  problem.residuals = [&](const Eigen::VectorXd& x) { return residuals(data, predict(from_vector(x, base)), options); };
  problem.lower.resize(kCount), problem.upper.resize(kCount), problem.scale.resize(kCount);
  for (int k = 0; k < kCount; ++k) {
    problem.lower[k] = kParameters[k].lower, problem.upper[k] = kParameters[k].upper, problem.scale[k] = kParameters[k].scale;
  }
  const Eigen::VectorXd x0 = to_vector(out.before).cwiseMax(problem.lower).cwiseMin(problem.upper);
  const Eigen::VectorXd r0 = problem.residuals(x0);

  // What the plate cannot determine is held at its value before: the directions of the scaled Jacobian's
  // smallest singular values, fixing the parameters least informed first.
  core::LeastSquaresSettings settings;
  settings.max_iterations = options.max_iterations;
  settings.undetermined_ratio = 1e-4;
  {
    core::LeastSquaresProblem probe = problem;
    core::LevenbergMarquardt start(probe, x0, settings);
    const auto stats = *start.result(true).statistics;
    // Each column to unit length: what decides identifiability is how nearly the parameters' effects on the marks
    // coincide, not how large one of them is in its own units (a delay moves every end by far more than a 5 %
    // compliance change moves a point, and would otherwise hide all the rest).
    Eigen::MatrixXd scaled = stats.jacobian;
    for (int k = 0; k < kCount; ++k) {
      const double norm = scaled.col(k).norm();
      if (norm > 0.0) scaled.col(k) /= norm;
    }
    // Timing first, then the field's gradients and its cross terms, its constant scales last.
    const std::vector<int> preference{12, 11, 10, 9, 8, 7, 2, 5, 1, 4, 6, 0, 3};
    problem.fixed.assign(kCount, false);
    for (const int k : core::parameters_to_fix(scaled, settings.undetermined_ratio, preference)) problem.fixed[static_cast<std::size_t>(k)] = true;
  }
  core::LevenbergMarquardt solver(problem, x0, settings);
  out.stop = solver.run();
  const core::LeastSquaresResult result = solver.result(true);
  out.iterations = result.iterations;
  out.after = from_vector(result.x, base);
  const Eigen::VectorXd errors = result.statistics ? result.statistics->standard_errors() : Eigen::VectorXd::Zero(kCount);
  for (int k = 0; k < kCount; ++k) {
    const bool held = problem.fixed[static_cast<std::size_t>(k)];
    out.values.push_back({kParameters[k].name, x0[k], result.x[k], held ? 0.0 : errors[k], !held});
  }

  // Each mark's misfit before and after.
  const auto before = predict(out.before), after = predict(out.after);
  double sum_before = 0.0, sum_after = 0.0;
  int count = 0;
  for (const auto& d : data) {
    MarkFit f;
    f.id = d.id;
    f.s_m = d.s;
    f.deviation_before_m = normal_distances(d.points, before[d.pulse].points_m);
    f.deviation_after_m = normal_distances(d.points, after[d.pulse].points_m);
    for (std::size_t k = 0; k < d.points.size(); ++k) {
      const double b = f.deviation_before_m[k], a = f.deviation_after_m[k];
      f.rms_before_m += b * b, f.rms_after_m += a * a;
      f.max_before_m = std::max(f.max_before_m, std::abs(b)), f.max_after_m = std::max(f.max_after_m, std::abs(a));
      sum_before += b * b, sum_after += a * a, ++count;
    }
    f.rms_before_m = std::sqrt(f.rms_before_m / static_cast<double>(d.points.size()));
    f.rms_after_m = std::sqrt(f.rms_after_m / static_cast<double>(d.points.size()));
    if (d.ends && !before[d.pulse].points_m.empty()) f.end_before_m = (d.points.back() - before[d.pulse].points_m.back()).dot(d.end_direction);
    if (d.ends && !after[d.pulse].points_m.empty()) f.end_after_m = (d.points.back() - after[d.pulse].points_m.back()).dot(d.end_direction);
    out.marks.push_back(std::move(f));
  }
  out.rms_before_m = std::sqrt(sum_before / std::max(count, 1));
  out.rms_after_m = std::sqrt(sum_after / std::max(count, 1));
  out.residuals = static_cast<int>(r0.size());

  // m·C after over before along x and y at each station's centre, (S·C·S)ii / Cii, with its uncertainty (the
  // delta method over the correction's nine coefficients, by central differences).
  std::map<std::string, std::pair<Vec2, int>> stations;
  for (const auto& m : plate.strokes) {
    auto& [sum, n] = stations[m.id.substr(0, m.id.find('-'))];
    if (n == 0) sum = Vec2::Zero();
    sum += m.kind == StrokeKind::arc ? m.centre_m : Vec2(0.5 * (m.start_m + m.end_m)), ++n;
  }
  const auto scale_at = [&](const Eigen::VectorXd& x, const Vec2& p) {
    const Mat2 C = model.compliance(p), S = from_vector(x, base).correction.matrix(p);
    const Mat2 Q = S * C * S;
    return Vec2(Q(0, 0) / C(0, 0), Q(1, 1) / C(1, 1));
  };
  for (const auto& [name, entry] : stations) {
    Identification::PointScale ps;
    ps.point_m = entry.first / entry.second;
    ps.scale = scale_at(result.x, ps.point_m);
    if (result.statistics) {
      Eigen::MatrixXd g(2, 9);
      for (int k = 0; k < 9; ++k) {
        Eigen::VectorXd up = result.x, down = result.x;
        up[k] += 1e-6, down[k] -= 1e-6;
        g.col(k) = (scale_at(up, ps.point_m) - scale_at(down, ps.point_m)) / 2e-6;
      }
      const Eigen::Matrix2d cov = g * result.statistics->covariance.topLeftCorner(9, 9) * g.transpose();
      ps.sigma = {std::sqrt(std::max(0.0, cov(0, 0))), std::sqrt(std::max(0.0, cov(1, 1)))};
    }
    out.scales.push_back(ps);
  }
  return out;
}

}  // namespace stiffpath::calibration
