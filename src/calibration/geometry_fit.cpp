// Geometry calibration by least squares: start frame by Umeyama, the gauge and weak directions held, uncertainties.
#include "stiffpath/calibration/geometry_fit.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/kinematics/five_bar.hpp"

namespace stiffpath::calibration {

namespace {
using P = GeometryParameter;
constexpr int idx(P p) { return static_cast<int>(p); }

constexpr int kHoldOrder[] = {idx(P::left_actuator_x),  idx(P::left_actuator_y), idx(P::theta1_zero),
                              idx(P::right_actuator_x), idx(P::right_actuator_y), idx(P::theta2_zero),
                              idx(P::left_proximal),    idx(P::right_proximal),   idx(P::left_distal),
                              idx(P::right_distal)};

// Shares of a direction below this are left out of its description.
constexpr double kShareShown = 0.05;

// The rigid transform that best maps the robot-plane points onto the readings: 3-D (Umeyama, without scale)
// when the readings have z; planar readings try the plane as seen from above and from below (mirrored).
struct StartFrame {
  InstrumentFrame frame;
  bool mirrored = false;
};

StartFrame start_frame(const std::vector<kinematics::Vec2>& robot, const GeometryReadings& readings) {
  const auto n = static_cast<Eigen::Index>(robot.size());
  StartFrame best;
  if (readings.has_z) {
    Eigen::Matrix3Xd src(3, n), dst(3, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      src.col(i) << robot[static_cast<std::size_t>(i)], 0.0;
      dst.col(i) = readings.rows[static_cast<std::size_t>(i)].point_m;
    }
    const Eigen::Matrix4d T = Eigen::umeyama(src, dst, false);
    best.frame.rotation = T.topLeftCorner<3, 3>();
    best.frame.translation_m = T.topRightCorner<3, 1>();
    return best;
  }
  // Planar: the rotation angle that best maps the centred points is atan2(Σ src × dst, Σ src · dst).
  double best_cost = std::numeric_limits<double>::infinity();
  for (const bool mirrored : {false, true}) {
    kinematics::Vec2 src_mean = kinematics::Vec2::Zero(), dst_mean = kinematics::Vec2::Zero();
    std::vector<kinematics::Vec2> src(robot.size());
    for (std::size_t i = 0; i < robot.size(); ++i) {
      src[i] = kinematics::Vec2(robot[i].x(), mirrored ? -robot[i].y() : robot[i].y());
      src_mean += src[i] / static_cast<double>(n);
      dst_mean += readings.rows[i].point_m.head<2>() / static_cast<double>(n);
    }
    double dot = 0.0, cross = 0.0;
    for (std::size_t i = 0; i < robot.size(); ++i) {
      const kinematics::Vec2 a = src[i] - src_mean, b = readings.rows[i].point_m.head<2>() - dst_mean;
      dot += a.dot(b);
      cross += a.x() * b.y() - a.y() * b.x();
    }
    const Eigen::Rotation2Dd turn(std::atan2(cross, dot));
    const kinematics::Vec2 shift = dst_mean - turn * src_mean;
    double cost = 0.0;
    for (std::size_t i = 0; i < robot.size(); ++i) cost += (turn * src[i] + shift - readings.rows[i].point_m.head<2>()).squaredNorm();
    if (cost < best_cost) {
      best_cost = cost;
      best.mirrored = mirrored;
      // The mirror y → −y of the plane is the turn by π about x in space (z → −z as well): a proper rotation.
      Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
      R.topLeftCorner<2, 2>() = turn.toRotationMatrix();
      if (mirrored) R = R * Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
      best.frame.rotation = R;
      best.frame.translation_m << shift, 0.0;
    }
  }
  return best;
}
}  // namespace

Eigen::VectorXd parameter_scales(const GeometryFitSettings& s) {
  Eigen::VectorXd scale(kGeometryParameters);
  scale << s.actuator_tolerance_m, s.actuator_tolerance_m, s.actuator_tolerance_m, s.actuator_tolerance_m,
      s.link_tolerance_m, s.link_tolerance_m, s.link_tolerance_m, s.link_tolerance_m, s.zero_tolerance_rad,
      s.zero_tolerance_rad, s.instrument_rotation_scale_rad, s.instrument_rotation_scale_rad,
      s.instrument_rotation_scale_rad, s.instrument_translation_scale_m, s.instrument_translation_scale_m,
      s.instrument_translation_scale_m;
  return scale;
}

std::span<const int> hold_order() noexcept { return kHoldOrder; }

GeometryFitResult fit_geometry(const kinematics::Robot& nominal, const GeometryReadings& readings,
                               const GeometryFitSettings& settings) {
  const auto m = static_cast<Eigen::Index>(readings.rows.size());
  const int dims = readings.has_z ? 3 : 2;
  if (m == 0) throw Error(SourceLocation{readings.source}, "no readings");
  if (!(settings.noise_sigma_m > 0.0)) throw Error("geometry fit: the instrument's noise must be positive");
  // The robot file's end points: every pose must close.
  const kinematics::FiveBar five_bar(nominal.geometry, {0.0, 1e300, 0.0});
  std::vector<kinematics::Vec2> nominal_points;
  for (const auto& r : readings.rows) {
    try {
      nominal_points.push_back(five_bar.forward_checked(r.q_rad));
    } catch (const Error& e) {
      throw Error(SourceLocation{readings.source, r.line, 0},
                  fmt::format("robot {}: {} (with the robot file's geometry)", nominal.name, e.message()));
    }
  }
  const StartFrame start = start_frame(nominal_points, readings);
  const GeometryModel model(nominal, start.frame.rotation);
  const Eigen::VectorXd x_nominal = model.pack(nominal.geometry, start.frame);

  // Parameters that do not apply: planar readings see neither the frame's tilt nor its height.
  std::vector<bool> applicable(kGeometryParameters, true);
  if (!readings.has_z) {
    for (P p : {P::instrument_rotation_x, P::instrument_rotation_y, P::instrument_z}) applicable[static_cast<std::size_t>(idx(p))] = false;
  }
  core::LeastSquaresProblem problem;
  problem.residuals = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd r(m * dims);
    const InstrumentFrame frame = model.instrument(x);
    const kinematics::FiveBar fb(model.geometry(x), {0.0, 1e300, 0.0});
    for (Eigen::Index i = 0; i < m; ++i) {
      const auto& row = readings.rows[static_cast<std::size_t>(i)];
      const Eigen::Vector3d d = row.point_m - frame.to_instrument(fb.forward(row.q_rad));
      r.segment(i * dims, dims) = d.head(dims);
    }
    return r;
  };
  problem.scale = parameter_scales(settings);
  core::LeastSquaresSettings solver = settings.solver;

  // "Before": the robot file's geometry, the instrument's frame fitted alone.
  problem.fixed.assign(kGeometryParameters, true);
  for (int k = kRobotParameters; k < kGeometryParameters; ++k) problem.fixed[static_cast<std::size_t>(k)] = !applicable[static_cast<std::size_t>(k)];
  core::LevenbergMarquardt frame_only(problem, x_nominal, solver);
  frame_only.run();
  const Eigen::VectorXd x_before = frame_only.x();
  const Eigen::VectorXd r_before = frame_only.residuals();

  // What the readings determine, at the start: the scaled Jacobian of every applicable parameter. A direction
  // is determined when its singular value is at least the noise σ, i.e. when the readings fix it to better than
  // one prior scale unit (a tolerance of the parts).
  std::vector<int> candidates;
  for (int k = 0; k < kGeometryParameters; ++k) {
    if (applicable[static_cast<std::size_t>(k)]) candidates.push_back(k);
  }
  problem.fixed.assign(kGeometryParameters, false);
  for (int k = 0; k < kGeometryParameters; ++k) problem.fixed[static_cast<std::size_t>(k)] = !applicable[static_cast<std::size_t>(k)];
  const core::LevenbergMarquardt probe(problem, x_before, solver);
  const Eigen::MatrixXd J0 = probe.result(true).statistics->jacobian;
  Eigen::MatrixXd Js(J0.rows(), static_cast<Eigen::Index>(candidates.size()));
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    Js.col(static_cast<Eigen::Index>(j)) = J0.col(candidates[j]) * problem.scale(candidates[j]);
  }
  const double largest = Js.size() > 0 ? Eigen::JacobiSVD<Eigen::MatrixXd>(Js).singularValues()(0) : 0.0;
  const double ratio = largest > 0.0 ? std::max(solver.undetermined_ratio, settings.noise_sigma_m / largest) : 1.0;
  const core::LeastSquaresStatistics seen = core::analyse_jacobian(Js, r_before, candidates, kGeometryParameters, {},
                                                                   ratio, settings.noise_sigma_m);
  std::vector<int> preference;
  for (const int k : kHoldOrder) {
    const auto it = std::find(candidates.begin(), candidates.end(), k);
    if (it != candidates.end()) preference.push_back(static_cast<int>(it - candidates.begin()));
  }
  const std::vector<int> hold = core::parameters_to_fix(Js, ratio, preference);

  GeometryFitResult out;
  out.spatial = readings.has_z;
  out.mirrored = start.mirrored;
  out.readings = static_cast<int>(m);
  for (Eigen::Index k = seen.rank; k < seen.singular_values.size(); ++k) {
    UndeterminedDirection d;
    d.singular_value_over_noise = seen.singular_values(k) / settings.noise_sigma_m;
    for (std::size_t j = 0; j < candidates.size(); ++j) {
      const double v = seen.directions(static_cast<Eigen::Index>(j), k);
      if (std::abs(v) >= kShareShown) d.shares.emplace_back(parameter_name(candidates[j]), v);
    }
    std::sort(d.shares.begin(), d.shares.end(),
              [](const auto& a, const auto& b) { return std::abs(a.second) > std::abs(b.second); });
    out.undetermined.push_back(d);
  }
  for (const int j : hold) problem.fixed[static_cast<std::size_t>(candidates[static_cast<std::size_t>(j)])] = true;
  const int fitted = static_cast<int>(std::count(problem.fixed.begin(), problem.fixed.end(), false));
  if (m * dims <= fitted) {
    throw Error(SourceLocation{readings.source},
                fmt::format("{} readings give {} coordinates, not more than the {} parameters to fit: measure more "
                            "poses (stiffpath geometry plan)",
                            m, m * dims, fitted));
  }

  // The fit itself, from the frame-only start (the robot file's geometry), with every determined parameter free.
  core::LevenbergMarquardt lm(problem, x_before, solver);
  lm.run();
  const core::LeastSquaresResult res = lm.result(true);
  out.x = res.x;
  out.start_rotation = model.start_rotation();
  out.geometry = model.geometry(res.x);
  out.instrument = model.instrument(res.x);
  out.stop = res.stop;
  out.iterations = res.iterations;
  out.fitted = fitted;
  out.covariance = res.statistics->covariance;
  out.sigma_estimated_m = res.statistics->sigma;
  const Eigen::VectorXd se = res.statistics->standard_errors();
  for (int k = 0; k < kGeometryParameters; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    GeometryParameterResult p;
    p.name = parameter_name(k);
    p.nominal = k < kRobotParameters ? x_nominal(k) : x_before(k);
    p.value = res.x(k);
    p.applicable = applicable[uk];
    p.fixed = problem.fixed[uk] && applicable[uk];
    p.sigma = problem.fixed[uk] ? 0.0 : se(k);
    out.parameters.push_back(p);
  }
  double sum_before = 0.0, sum_after = 0.0;
  for (Eigen::Index i = 0; i < m; ++i) {
    const auto& row = readings.rows[static_cast<std::size_t>(i)];
    ReadingResidual rr;
    rr.line = row.line;
    rr.q_rad = row.q_rad;
    rr.before_m.head(dims) = r_before.segment(i * dims, dims);
    rr.after_m.head(dims) = res.residuals.segment(i * dims, dims);
    sum_before += rr.before_m.squaredNorm();
    sum_after += rr.after_m.squaredNorm();
    out.max_before_m = std::max(out.max_before_m, rr.before_m.norm());
    out.max_after_m = std::max(out.max_after_m, rr.after_m.norm());
    out.residuals.push_back(rr);
  }
  out.rms_before_m = std::sqrt(sum_before / static_cast<double>(m * dims));
  out.rms_after_m = std::sqrt(sum_after / static_cast<double>(m * dims));
  return out;
}

kinematics::Robot calibrated_robot(const kinematics::Robot& nominal, const GeometryFitResult& fit,
                                   std::vector<std::string>* notes) {
  kinematics::Robot robot = nominal;
  robot.geometry = fit.geometry;
  robot.preset = false;
  robot.description = nominal.description.empty() ? "geometry calibrated" : nominal.description + "; geometry calibrated";
  if (!robot.compliance.table.empty() && !robot.compliance.table.builtin) {
    robot.compliance.table.path = std::filesystem::absolute(robot.compliance.table.path).lexically_normal().string();
  }
  if (!robot.compliance.model.empty()) {
    if (notes) {
      notes->push_back(fmt::format("compliance.model {} was fitted for the robot file's geometry and is left out; "
                                   "{}fit one for the calibrated robot: stiffpath fit --robot <calibrated file> -o model.json",
                                   nominal.compliance.model.label(),
                                   robot.compliance.table.empty() ? "" : "commands fit the table at start-up meanwhile; "));
    }
    robot.compliance.model = {};
  }
  (void)robot.five_bar();  // the calibrated geometry must leave a workspace (throws otherwise)
  if (robot.home_m && !robot.refusal(*robot.home_m).empty()) {
    if (notes) notes->push_back("home_mm is not reachable with the calibrated geometry and is left out: " + robot.refusal(*robot.home_m));
    robot.home_m.reset();
  }
  return robot;
}

}  // namespace stiffpath::calibration
