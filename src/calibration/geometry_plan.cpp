// Poses for a geometry calibration: greedy D-optimal selection with exchange over the reachable lattice; virtual readings.
#include "stiffpath/calibration/geometry_plan.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <random>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/least_squares.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::calibration {

namespace {
using P = GeometryParameter;
constexpr int idx(P p) { return static_cast<int>(p); }

// The parameters a planar reading informs (the instrument's tilt and height are for spatial readings).
constexpr int kPlanar[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, idx(P::instrument_rotation_z), idx(P::instrument_x), idx(P::instrument_y)};
// The finite-difference step, in units of each parameter's scale.
constexpr double kStep = 1e-6;
// A small ridge on the information matrix (relative to its mean diagonal) so that the first greedy picks, which
// cannot yet determine every parameter, still compare by the volume they add.
constexpr double kRidge = 1e-9;

// Rows 2i, 2i+1: the scaled Jacobian of pose i's planar reading (instrument frame = robot frame) over kPlanar.
Eigen::MatrixXd scaled_jacobian(const kinematics::Robot& robot, const std::vector<kinematics::Vec2>& q,
                                const GeometryFitSettings& settings) {
  const GeometryModel model(robot, Eigen::Matrix3d::Identity());
  const Eigen::VectorXd x0 = model.pack(robot.geometry, InstrumentFrame{});
  const Eigen::VectorXd scale = parameter_scales(settings);
  const auto n = static_cast<Eigen::Index>(q.size());
  Eigen::MatrixXd J(2 * n, static_cast<Eigen::Index>(std::size(kPlanar)));
  for (std::size_t j = 0; j < std::size(kPlanar); ++j) {
    const int k = kPlanar[j];
    const double h = kStep * scale(k);
    Eigen::VectorXd xp = x0, xm = x0;
    xp(k) += h;
    xm(k) -= h;
    const kinematics::FiveBarGeometry gp = model.geometry(xp), gm = model.geometry(xm);
    const InstrumentFrame fp = model.instrument(xp), fm = model.instrument(xm);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto& qi = q[static_cast<std::size_t>(i)];
      const Eigen::Vector3d d = fp.to_instrument(GeometryModel::end_point(gp, qi)) - fm.to_instrument(GeometryModel::end_point(gm, qi));
      J.block<2, 1>(2 * i, static_cast<Eigen::Index>(j)) = d.head<2>() / (2.0 * kStep);  // per scale unit
    }
  }
  return J;
}

// The columns (over kPlanar) that a plan of `poses` poses spread like the candidates leaves undetermined.
std::vector<int> held_columns(const Eigen::MatrixXd& J_candidates, int poses, const GeometryFitSettings& settings) {
  const double rows = static_cast<double>(J_candidates.rows()) / 2.0;
  const Eigen::MatrixXd Jp = J_candidates * std::sqrt(poses / rows);
  const double largest = Eigen::JacobiSVD<Eigen::MatrixXd>(Jp).singularValues()(0);
  const double ratio = std::max(settings.solver.undetermined_ratio, settings.noise_sigma_m / largest);
  // kPlanar's first entries are the robot's parameters themselves, so fit_geometry's hold order applies as it is.
  return core::parameters_to_fix(Jp, ratio, hold_order());
}

std::vector<int> free_columns(const std::vector<int>& held) {
  std::vector<int> free;
  for (int j = 0; j < static_cast<int>(std::size(kPlanar)); ++j) {
    if (std::find(held.begin(), held.end(), j) == held.end()) free.push_back(j);
  }
  return free;
}

Eigen::MatrixXd rows_of(const Eigen::MatrixXd& J, std::size_t pose, const std::vector<int>& free) {
  Eigen::MatrixXd out(2, static_cast<Eigen::Index>(free.size()));
  for (std::size_t j = 0; j < free.size(); ++j) out.col(static_cast<Eigen::Index>(j)) = J.block<2, 1>(2 * static_cast<Eigen::Index>(pose), free[j]);
  return out;
}

double log_det(const Eigen::MatrixXd& M) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
  return ldlt.vectorD().array().max(1e-300).log().sum();
}
}  // namespace

GeometryPlan plan_geometry_poses(const kinematics::Robot& robot, const GeometryPlanSettings& settings) {
  if (settings.poses < 4 || settings.poses > kMaxPlannedPoses) {
    throw Error(fmt::format("geometry plan: the number of poses must lie in [4, {}], got {}", kMaxPlannedPoses, settings.poses));
  }
  const auto& g = robot.geometry;
  // The reachable region's bounding box, cut to the requested region.
  auto box = compliance::GridBounds::none();
  for (int i = 0; i < 2; ++i) {
    const double reach = g.proximal_m[i] + g.distal_m[i];
    box.include(g.actuator_m[i] + kinematics::Vec2(reach, reach));
    box.include(g.actuator_m[i] - kinematics::Vec2(reach, reach));
  }
  if (settings.region) {
    box = {std::max(box.x_min, settings.region->x_min), std::min(box.x_max, settings.region->x_max),
           std::max(box.y_min, settings.region->y_min), std::min(box.y_max, settings.region->y_max)};
    if (!(box.x_max > box.x_min && box.y_max > box.y_min)) throw Error("geometry plan: the region lies outside the robot's reach");
  }
  GeometryPlan plan;
  const double area = (box.x_max - box.x_min) * (box.y_max - box.y_min);
  // A first lattice finds the reachable share of the box; the second has about `candidates` reachable points.
  double step = std::sqrt(area / std::max(settings.candidates, 16));
  const kinematics::FiveBar five_bar = robot.five_bar();
  std::vector<kinematics::Vec2> points, q;
  for (int pass = 0; pass < 2; ++pass) {
    points.clear();
    q.clear();
    for (double x = box.x_min + step / 2; x < box.x_max; x += step) {
      for (double y = box.y_min + step / 2; y < box.y_max; y += step) {
        const kinematics::Vec2 p(x, y);
        if (!robot.refusal(p).empty()) continue;
        const kinematics::Vec2 qp = robot.inverse(p);
        if (!(five_bar.condition_number(qp) <= settings.max_condition_number)) continue;
        points.push_back(p);
        q.push_back(qp);
      }
    }
    if (pass == 0 && !points.empty()) {
      step *= std::sqrt(static_cast<double>(points.size()) / settings.candidates);
    }
  }
  if (static_cast<int>(points.size()) < settings.poses) {
    throw Error(fmt::format("geometry plan: the robot reaches only {} candidate points{} with a condition number of at "
                            "most {:g} (lattice {:.2f} mm), fewer than the {} poses asked for",
                            points.size(), settings.region ? " in the region" : "", settings.max_condition_number,
                            step * 1e3, settings.poses));
  }
  plan.reachable = points;
  plan.max_condition_number = std::min(settings.max_condition_number, robot.margin.max_condition_number);
  plan.lattice_step_m = step;
  plan.min_separation_m = settings.min_separation_fraction * std::sqrt(static_cast<double>(points.size()) * step * step / settings.poses);

  const Eigen::MatrixXd J = scaled_jacobian(robot, q, settings.fit);
  const std::vector<int> held = held_columns(J, settings.poses, settings.fit);
  for (const int j : held) plan.held.emplace_back(parameter_name(kPlanar[j]));
  const std::vector<int> free = free_columns(held);
  const auto nf = static_cast<Eigen::Index>(free.size());
  std::vector<Eigen::MatrixXd> rows(points.size());
  double trace = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    rows[i] = rows_of(J, i, free);
    trace += rows[i].squaredNorm();
  }
  const Eigen::MatrixXd ridge = kRidge * trace / static_cast<double>(points.size() * static_cast<std::size_t>(nf)) *
                                Eigen::MatrixXd::Identity(nf, nf);
  const auto far_enough = [&](std::size_t c, const std::vector<std::size_t>& chosen, std::size_t except) {
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      if (k != except && (points[chosen[k]] - points[c]).norm() < plan.min_separation_m) return false;
    }
    return true;
  };
  const auto information = [&](const std::vector<std::size_t>& chosen, std::size_t except) {
    Eigen::MatrixXd M = ridge;
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      if (k != except) M += rows[chosen[k]].transpose() * rows[chosen[k]];
    }
    return M;
  };
  // The candidate that adds the most volume to M: log det(I + Jc M⁻¹ Jcᵀ).
  const auto best_addition = [&](const Eigen::MatrixXd& M, const std::vector<std::size_t>& chosen, std::size_t except,
                                 double& gain) {
    const Eigen::MatrixXd Minv = M.ldlt().solve(Eigen::MatrixXd::Identity(nf, nf));
    std::size_t best = points.size();
    gain = -1.0;
    for (std::size_t c = 0; c < points.size(); ++c) {
      if (!far_enough(c, chosen, except)) continue;
      const Eigen::Matrix2d S = Eigen::Matrix2d::Identity() + rows[c] * Minv * rows[c].transpose();
      const double v = std::log(S.determinant());
      if (v > gain) {
        gain = v;
        best = c;
      }
    }
    return best;
  };
  std::vector<std::size_t> chosen;
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  while (static_cast<int>(chosen.size()) < settings.poses) {
    double gain = 0.0;
    const std::size_t c = best_addition(information(chosen, kNone), chosen, kNone, gain);
    if (c == points.size()) {
      throw Error(fmt::format("geometry plan: only {} poses fit {:.1f} mm apart in the region; ask for fewer poses or a "
                              "smaller min_separation_fraction",
                              chosen.size(), plan.min_separation_m * 1e3));
    }
    chosen.push_back(c);
  }
  for (int pass = 0; pass < settings.exchange_passes; ++pass) {
    bool swapped = false;
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      const Eigen::MatrixXd without = information(chosen, k);
      double gain = 0.0;
      const std::size_t c = best_addition(without, chosen, k, gain);
      const Eigen::Matrix2d S = Eigen::Matrix2d::Identity() +
                                rows[chosen[k]] * without.ldlt().solve(rows[chosen[k]].transpose());
      if (c != points.size() && c != chosen[k] && gain > std::log(S.determinant()) + 1e-9) {
        chosen[k] = c;
        swapped = true;
      }
    }
    if (!swapped) break;
  }
  const Eigen::MatrixXd M = information(chosen, kNone) - ridge;
  plan.log_det = log_det(M);
  // Predicted σ of each parameter: noise² · M⁻¹, unscaled.
  const Eigen::MatrixXd cov = settings.fit.noise_sigma_m * settings.fit.noise_sigma_m * M.ldlt().solve(Eigen::MatrixXd::Identity(nf, nf));
  const Eigen::VectorXd scale = parameter_scales(settings.fit);
  plan.predicted_sigma.assign(kGeometryParameters, 0.0);
  for (Eigen::Index j = 0; j < nf; ++j) {
    const int k = kPlanar[free[static_cast<std::size_t>(j)]];
    plan.predicted_sigma[static_cast<std::size_t>(k)] = std::sqrt(std::max(cov(j, j), 0.0)) * scale(k);
  }
  // A measuring order: nearest neighbour from the pose nearest the robot's home (else the first chosen).
  std::vector<std::size_t> order;
  std::vector<bool> used(chosen.size(), false);
  const kinematics::Vec2 home = robot.home_m.value_or(points[chosen.front()]);
  kinematics::Vec2 at = home;
  for (std::size_t n = 0; n < chosen.size(); ++n) {
    std::size_t next = 0;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < chosen.size(); ++k) {
      const double d = (points[chosen[k]] - at).norm();
      if (!used[k] && d < best) {
        best = d;
        next = k;
      }
    }
    used[next] = true;
    at = points[chosen[next]];
    order.push_back(chosen[next]);
  }
  for (const std::size_t c : order) plan.poses.push_back({q[c], points[c], five_bar.condition_number(q[c])});
  return plan;
}

double geometry_log_det(const kinematics::Robot& robot, const std::vector<kinematics::Vec2>& q_rad,
                        const GeometryPlanSettings& settings) {
  // The held parameters as the plan would hold them for this many poses over the robot's reach.
  GeometryPlanSettings probe = settings;
  probe.poses = static_cast<int>(q_rad.size());
  const Eigen::MatrixXd J = scaled_jacobian(robot, q_rad, settings.fit);
  const std::vector<int> free = free_columns(held_columns(J, probe.poses, settings.fit));
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(free.size()), static_cast<Eigen::Index>(free.size()));
  for (std::size_t i = 0; i < q_rad.size(); ++i) {
    const Eigen::MatrixXd r = rows_of(J, i, free);
    M += r.transpose() * r;
  }
  return log_det(M);
}

void save_geometry_plan(const GeometryPlan& plan, const std::string& path) {
  core::AtomicFile file(path);
  auto& out = file.stream();
  out << "pose,theta1_deg,theta2_deg,x_mm,y_mm,condition_number\n";
  int n = 0;
  for (const auto& p : plan.poses) {
    out << fmt::format("g{},{:.6f},{:.6f},{:.4f},{:.4f},{:.3f}\n", ++n, units::rad_to_deg(p.q_rad.x()),
                       units::rad_to_deg(p.q_rad.y()), units::m_to_mm(p.p_m.x()), units::m_to_mm(p.p_m.y()),
                       p.condition_number);
  }
  file.commit();
}

std::vector<kinematics::Vec2> load_pose_angles(const std::string& path) {
  core::CsvReader csv(path);
  const auto c1 = csv.column("theta1_deg"), c2 = csv.column("theta2_deg");
  std::vector<kinematics::Vec2> out;
  while (csv.next()) {
    if (static_cast<int>(out.size()) == kMaxGeometryReadings) {
      throw Error(csv.where(), fmt::format("more than {} poses", kMaxGeometryReadings));
    }
    kinematics::Vec2 q;
    for (int i = 0; i < 2; ++i) {
      const auto col = i == 0 ? c1 : c2;
      const double v = csv.number(col);
      if (!(std::abs(v) <= kMaxJointReading_deg)) csv.fail(col, fmt::format("{} is beyond +-{:g} deg", v, kMaxJointReading_deg));
      q[i] = units::deg_to_rad(v);
    }
    out.push_back(q);
  }
  if (out.empty()) throw Error(SourceLocation{path}, "no poses");
  return out;
}

GeometryReadings simulate_geometry_readings(const kinematics::FiveBarGeometry& truth,
                                            const std::vector<kinematics::Vec2>& q_rad, const GeometryRehearsal& o) {
  if (!(o.noise_sigma_m >= 0.0) || o.readings_per_pose < 1) throw Error("virtual readings: noise must be >= 0 and readings >= 1");
  const kinematics::FiveBar fb(truth, {0.0, 1e300, 0.0});
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  GeometryReadings out{"virtual readings", o.spatial, {}};
  for (const auto& q : q_rad) {
    const Eigen::Vector3d exact = o.frame.to_instrument(fb.forward_checked(q));
    for (int k = 1; k <= o.readings_per_pose; ++k) {
      GeometryReading r;
      r.q_rad = q;
      r.reading = k;
      r.point_m = exact + o.noise_sigma_m * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      if (!o.spatial) r.point_m.z() = 0.0;
      out.rows.push_back(r);
    }
  }
  return out;
}

}  // namespace stiffpath::calibration
