// The structural (virtual-joint) C_true: arm chains of springs and beams, fitted to the robot's translations.
#include "stiffpath/simulation/structural_compliance.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

using compliance::Mat2;
using compliance::Vec2;
using Mat3 = Eigen::Matrix3d;

double& ArmCompliance::operator[](int k) noexcept {
  double* v[count] = {&actuator_rad_per_Nm, &proximal_bending_per_Nm2, &proximal_axial_per_N, &distal_bending_per_Nm2,
                      &distal_axial_per_N,  &elbow_rad_per_Nm,         &pin_m_per_N};
  return *v[k];
}
double ArmCompliance::operator[](int k) const noexcept { return const_cast<ArmCompliance&>(*this)[k]; }

namespace {

// G maps the wrench (Fx, Fy, M) at C to the wrench at P = C − r; Gᵀ maps P's small twist to C's.
Mat3 wrench_shift(const Vec2& r) {
  Mat3 g = Mat3::Identity();
  g(2, 0) = -r.y();
  g(2, 1) = r.x();
  return g;
}

// An element's compliance (local frame along `axis`) seen at C: Gᵀ R C_e Rᵀ G.
Mat3 at_end(const Mat3& local, const Vec2& axis, const Vec2& r) {
  Mat3 rot = Mat3::Identity();
  rot.topLeftCorner<2, 2>() << axis.x(), -axis.y(), axis.y(), axis.x();
  const Mat3 g = wrench_shift(r);
  return g.transpose() * rot * local * rot.transpose() * g;
}

// Cantilever of length L at its tip, local (axial, lateral, rotation): Euler–Bernoulli.
Mat3 beam(double L, double bending, double axial) {
  Mat3 c = Mat3::Zero();
  c(0, 0) = L * axial;
  c(1, 1) = L * L * L / 3.0 * bending;
  c(1, 2) = c(2, 1) = L * L / 2.0 * bending;
  c(2, 2) = L * bending;
  return c;
}

Mat3 rotational(double c) {
  Mat3 m = Mat3::Zero();
  m(2, 2) = c;
  return m;
}

}  // namespace

StructuralModel::StructuralModel(const kinematics::Robot& robot, std::array<ArmCompliance, 2> arms,
                                 compliance::GridBounds region, BaseCompliance base)
    : five_bar_(robot.five_bar()), arms_(arms), base_(base), region_(region) {
  for (double v : {base.x_m_per_N, base.y_m_per_N, base.rotation_rad_per_Nm}) {
    if (!(std::isfinite(v) && v >= 0.0)) throw Error("structural model: base compliances must be finite and ≥ 0");
  }
  for (const auto& arm : arms_) {
    for (int k = 0; k < ArmCompliance::count; ++k) {
      if (!(std::isfinite(arm[k]) && arm[k] >= 0.0)) throw Error("structural model: compliances must be finite and ≥ 0");
    }
  }
  set_outside_policy(compliance::OutsidePolicy::extrapolate);
}

Mat2 StructuralModel::compliance(const Vec2& p_in) const noexcept {
  // Beyond reach the structure is evaluated at the nearest point of the measured rectangle.
  Vec2 p = p_in;
  auto inverse = five_bar_.solve_inverse(p);
  if (inverse.status != kinematics::Reach::ok) {
    p = region_.clamp(p_in);
    inverse = five_bar_.solve_inverse(p);
  }
  const auto& g = five_bar_.geometry();
  const auto elbow = five_bar_.elbows(inverse.q);
  Mat2 stiffness = Mat2::Zero();
  for (int i = 0; i < 2; ++i) {
    const auto& a = arms_[static_cast<std::size_t>(i)];
    const Vec2 A = g.actuator_m[static_cast<std::size_t>(i)], B = elbow[static_cast<std::size_t>(i)];
    const double lp = g.proximal_m[static_cast<std::size_t>(i)], ld = g.distal_m[static_cast<std::size_t>(i)];
    const Vec2 e = (B - A) / lp, u = (p - B) / ld;
    Mat3 c = at_end(rotational(a.actuator_rad_per_Nm), e, p - A);
    c += at_end(beam(lp, a.proximal_bending_per_Nm2, a.proximal_axial_per_N), e, p - B);
    c += at_end(rotational(a.elbow_rad_per_Nm), u, p - B);
    c += at_end(beam(ld, a.distal_bending_per_Nm2, a.distal_axial_per_N), u, Vec2::Zero());
    c(0, 0) += a.pin_m_per_N;
    c(1, 1) += a.pin_m_per_N;
    // The pin at C carries no moment: the arm resists a force with the inverse of its translational block.
    stiffness += c.topLeftCorner<2, 2>().inverse();
  }
  // The base frame under both arms, in series with them: translation and rotation about the actuators' midpoint.
  Mat3 base = Mat3::Zero();
  base(0, 0) = base_.x_m_per_N;
  base(1, 1) = base_.y_m_per_N;
  base(2, 2) = base_.rotation_rad_per_Nm;
  const Vec2 a0 = 0.5 * (g.actuator_m[0] + g.actuator_m[1]);
  return stiffness.inverse() + at_end(base, Vec2(1, 0), p - a0).topLeftCorner<2, 2>();
}

nlohmann::json StructuralModel::parameters() const {
  nlohmann::json arms = nlohmann::json::array();
  for (const auto& a : arms_) {
    arms.push_back({{"actuator_rad_per_Nm", a.actuator_rad_per_Nm},
                    {"proximal_bending_per_Nm2", a.proximal_bending_per_Nm2},
                    {"proximal_axial_per_N", a.proximal_axial_per_N},
                    {"distal_bending_per_Nm2", a.distal_bending_per_Nm2},
                    {"distal_axial_per_N", a.distal_axial_per_N},
                    {"elbow_rad_per_Nm", a.elbow_rad_per_Nm},
                    {"pin_m_per_N", a.pin_m_per_N}});
  }
  return {{"arms", arms},
          {"base", {{"x_m_per_N", base_.x_m_per_N}, {"y_m_per_N", base_.y_m_per_N},
                    {"rotation_rad_per_Nm", base_.rotation_rad_per_Nm}}}};
}

namespace {

struct Cell {
  Vec2 p, force;
  double value;
  int axis;    // 0: dx, 1: dy
  int series;  // one load series: point × direction × axis
};

std::vector<Cell> cells_of(const measurement::DisplacementTable& table) {
  std::vector<Cell> cells;
  std::vector<std::string> series;
  const auto series_of = [&](const measurement::DisplacementRow& r, int axis) {
    const std::string key = fmt::format("{}|{}|{}", r.point, measurement::to_string(r.direction), axis);
    const auto it = std::find(series.begin(), series.end(), key);
    if (it != series.end()) return static_cast<int>(it - series.begin());
    series.push_back(key);
    return static_cast<int>(series.size()) - 1;
  };
  for (const auto& r : table.rows) {
    const Vec2 f = r.force_N * Vec2(measurement::direction_x(r.direction), measurement::direction_y(r.direction));
    if (r.dx_m) cells.push_back({{r.x_m, r.y_m}, f, *r.dx_m, 0, series_of(r, 0)});
    if (r.dy_m) cells.push_back({{r.x_m, r.y_m}, f, *r.dy_m, 1, series_of(r, 1)});
  }
  return cells;
}

compliance::GridBounds region_of(const measurement::DisplacementTable& table) {
  auto b = compliance::GridBounds::none();
  for (const auto& r : table.rows) b.include({r.x_m, r.y_m});
  return b;
}

// Residuals C·F + n_s − d of every cell, n_s the offset of its load series (eq. 4.8's intercept: the readings
// at step 0 carry settling and hysteresis that no compliance reproduces), set to the series' mean misfit.
Eigen::VectorXd residuals(const compliance::Model& m, const std::vector<Cell>& cells) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(cells.size()));
  int n_series = 0;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    r(static_cast<Eigen::Index>(k)) = (m.compliance(cells[k].p) * cells[k].force)(cells[k].axis) - cells[k].value;
    n_series = std::max(n_series, cells[k].series + 1);
  }
  std::vector<double> sum(static_cast<std::size_t>(n_series), 0.0), count(static_cast<std::size_t>(n_series), 0.0);
  for (std::size_t k = 0; k < cells.size(); ++k) {
    sum[static_cast<std::size_t>(cells[k].series)] += r(static_cast<Eigen::Index>(k));
    count[static_cast<std::size_t>(cells[k].series)] += 1.0;
  }
  for (std::size_t k = 0; k < cells.size(); ++k) {
    const auto s = static_cast<std::size_t>(cells[k].series);
    r(static_cast<Eigen::Index>(k)) -= sum[s] / count[s];
  }
  return r;
}

constexpr int kArmParams = 2 * ArmCompliance::count;
constexpr int kParams = kArmParams + 3;

std::array<ArmCompliance, 2> arms_from(const Eigen::VectorXd& log_c) {
  std::array<ArmCompliance, 2> arms;
  for (int k = 0; k < kArmParams; ++k) {
    arms[static_cast<std::size_t>(k / ArmCompliance::count)][k % ArmCompliance::count] = std::exp(log_c(k));
  }
  return arms;
}

BaseCompliance base_from(const Eigen::VectorXd& log_c) {
  return {std::exp(log_c(kArmParams)), std::exp(log_c(kArmParams + 1)), std::exp(log_c(kArmParams + 2))};
}

}  // namespace

StructuralFitReport structural_fit_report(const compliance::Model& model, const measurement::DisplacementTable& table) {
  const auto cells = cells_of(table);
  StructuralFitReport rep;
  const Eigen::VectorXd r = residuals(model, cells);
  rep.cells = static_cast<int>(cells.size());
  if (rep.cells == 0) return rep;
  rep.max_error_m = r.cwiseAbs().maxCoeff();
  rep.rms_error_m = std::sqrt(r.squaredNorm() / rep.cells);
  rep.within_23um = static_cast<int>((r.cwiseAbs().array() <= 23e-6).count());
  return rep;
}

std::shared_ptr<StructuralModel> fit_structural_model(const kinematics::Robot& robot,
                                                      const measurement::DisplacementTable& table,
                                                      StructuralFitReport* report) {
  const auto cells = cells_of(table);
  if (cells.size() < static_cast<std::size_t>(kParams)) {
    throw Error(SourceLocation{table.source}, "structural model: the table has too few translations (dx, dy) to fit");
  }
  const compliance::GridBounds region = region_of(table);
  auto cost = [&](const Eigen::VectorXd& x) {
    return residuals(StructuralModel(robot, arms_from(x), region, base_from(x)), cells);
  };
  // Starts: orders of magnitude of a small aluminium robot (actuator 1e-4 rad/N·m, 1/EI 1e-3 /N·m² …),
  // then each family of elements made dominant in turn.
  const std::array<double, ArmCompliance::count> typical{1e-4, 1e-3, 1e-8, 1e-3, 1e-8, 1e-4, 1e-7};
  Eigen::VectorXd best;
  double best_cost = 1e300;
  for (int start = -1; start < ArmCompliance::count; ++start) {
    Eigen::VectorXd x(kParams);
    for (int k = 0; k < kArmParams; ++k) {
      const int e = k % ArmCompliance::count;
      x(k) = std::log(typical[static_cast<std::size_t>(e)] * (e == start ? 30.0 : start < 0 ? 1.0 : 0.1));
    }
    x(kArmParams) = x(kArmParams + 1) = std::log(1e-7);  // base: 0.1 µm/N, 10 µrad/N·m
    x(kArmParams + 2) = std::log(1e-5);
    double lambda = 1e-2;
    Eigen::VectorXd r = cost(x);
    for (int it = 0; it < 150; ++it) {
      Eigen::MatrixXd J(r.size(), kParams);
      for (int k = 0; k < kParams; ++k) {
        Eigen::VectorXd xp = x;
        xp(k) += 1e-5;
        J.col(k) = (cost(xp) - r) / 1e-5;
      }
      const Eigen::MatrixXd A = J.transpose() * J;
      const Eigen::VectorXd g = J.transpose() * r;
      bool improved = false;
      for (int tries = 0; tries < 10 && !improved; ++tries) {
        Eigen::MatrixXd Ad = A;
        Ad.diagonal() += lambda * (A.diagonal().array() + 1e-30).matrix();
        Eigen::VectorXd xn = x - Ad.ldlt().solve(g);
        xn = xn.cwiseMax(std::log(1e-16)).cwiseMin(std::log(1.0));
        const Eigen::VectorXd rn = cost(xn);
        if (rn.squaredNorm() < r.squaredNorm()) {
          improved = (r.squaredNorm() - rn.squaredNorm()) > 1e-12 * r.squaredNorm();
          x = xn;
          r = rn;
          lambda = std::max(lambda / 3.0, 1e-9);
          if (!improved) break;
        } else {
          lambda *= 4.0;
        }
      }
      if (!improved) break;
    }
    if (r.squaredNorm() < best_cost) {
      best_cost = r.squaredNorm();
      best = x;
    }
  }
  auto model = std::make_shared<StructuralModel>(robot, arms_from(best), region, base_from(best));
  if (report) *report = structural_fit_report(*model, table);
  return model;
}

}  // namespace stiffpath::simulation
