// The structural C_true: a network of the arms' springs, links and parallelogram bars, fitted to the robot's translations.
#include "stiffpath/simulation/structural_compliance.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <vector>
#include <cmath>
#include <cstdint>
#include <string>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

using compliance::Mat2;
using compliance::Vec2;
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

double& ArmCompliance::operator[](int k) noexcept {
  double* v[count] = {&actuator_rad_per_Nm, &proximal_bending_per_Nm2, &proximal_axial_per_N,
                      &distal_axial_per_N,  &proximal_bar_m_per_N,     &distal_bar_m_per_N};
  return *v[k];
}
double ArmCompliance::operator[](int k) const noexcept { return const_cast<ArmCompliance&>(*this)[k]; }

namespace {

constexpr double kRigid = 1e-15;        // compliance floor: the element is rigid to far below 1 nm per kN
constexpr double kFreeRotation = 1e-9;  // N·m/rad on each body's ψ: keeps a body no bar holds determinate

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The inverse of a symmetric positive definite 3×3 by its cofactors (the twin evaluates C_true every step;
// a pivoting factorisation costs several times more). The physical floors keep the fitted networks' stiffnesses
// within ~10 decades of each other, well inside double precision.
Mat3 symmetric_inverse(const Mat3& m) {
  const double a = m(0, 0), b = m(0, 1), c = m(0, 2), d = m(1, 1), e = m(1, 2), f = m(2, 2);
  const double c00 = d * f - e * e, c01 = c * e - b * f, c02 = b * e - c * d;
  const double inv_det = 1.0 / (a * c00 + b * c01 + c * c02);
  Mat3 r;
  r(0, 0) = c00 * inv_det;
  r(0, 1) = r(1, 0) = c01 * inv_det;
  r(0, 2) = r(2, 0) = c02 * inv_det;
  r(1, 1) = (a * f - c * c) * inv_det;
  r(1, 2) = r(2, 1) = (b * c - a * e) * inv_det;
  r(2, 2) = (a * d - b * b) * inv_det;
  return r;
}

// The arm's pose at one platform position: actuator A, elbow B, unit vectors e (A → B) and u (B → C).
struct ArmPose {
  Vec2 A, B, e, u;
  double lp, ld;
};
using Pose = std::array<ArmPose, 2>;

// The pin at B passes no moment, so the actuator and the proximal cantilever hold B by the inverse of their
// translational compliance at B: κ·(l_p n)(l_p n)ᵀ (a unit rotation about A moves B by l_p·n) + l_p/EA·e·eᵀ +
// l_p³/3EI·n·nᵀ, diagonal in (e, n).
detail::ArmSprings arm_springs(const ArmCompliance& a, double lp, double ld) {
  detail::ArmSprings s;
  s.along_e = 1.0 / (lp * std::max(a.proximal_axial_per_N, kRigid));
  s.across_e = 1.0 / (a.actuator_rad_per_Nm * lp * lp + lp * lp * lp / 3.0 * std::max(a.proximal_bending_per_Nm2, kRigid));
  s.proximal_bar = 1.0 / std::max(a.proximal_bar_m_per_N, kRigid);
  s.distal_link = 1.0 / std::max(ld * a.distal_axial_per_N, kRigid);
  s.distal_bar = 1.0 / std::max(a.distal_bar_m_per_N, kRigid);
  s.proximal_offset = a.proximal_bar_offset_m;
  s.distal_offset = a.distal_bar_offset_m;
  return s;
}

std::array<detail::ArmSprings, 2> arm_springs(const std::array<ArmCompliance, 2>& arms, const kinematics::FiveBarGeometry& g) {
  return {arm_springs(arms[0], g.proximal_m[0], g.distal_m[0]), arm_springs(arms[1], g.proximal_m[1], g.distal_m[1])};
}

// Platform stiffness (x, y, ψ at C) of one arm: its elbow body (B, ψ_E) condensed out.
Mat3 arm_stiffness(const ArmPose& g, const detail::ArmSprings& a) {
  const Vec2 n(-g.e.y(), g.e.x());
  Mat3 kaa = Mat3::Zero();  // elbow body (B, ψ_E)
  kaa.topLeftCorner<2, 2>() = a.along_e * g.e * g.e.transpose() + a.across_e * n * n.transpose();
  kaa(2, 2) = kFreeRotation;
  // Proximal parallelogram bar: base pivot A + d → body pivot B + d, along e.
  const Vec3 gp(g.e.x(), g.e.y(), cross(a.proximal_offset, g.e));
  kaa.noalias() += a.proximal_bar * gp * gp.transpose();
  // Both the distal link and the distal bar join the elbow body to the platform along u, with h = (u, d × u) on
  // the platform's side and −h on the body's: each adds k·h·hᵀ to the platform's block and to the body's, and
  // −k·h·hᵀ to the coupling, so one symmetric B = Σ k·h·hᵀ carries all three.
  const Vec3 hl(g.u.x(), g.u.y(), 0.0), hb(g.u.x(), g.u.y(), cross(a.distal_offset, g.u));
  Mat3 bars = a.distal_link * hl * hl.transpose();
  bars.noalias() += a.distal_bar * hb * hb.transpose();
  kaa += bars;
  Mat3 kpp = bars;
  kpp(2, 2) += kFreeRotation;
  return kpp - bars * symmetric_inverse(kaa) * bars;
}

// The compliance at the measured point from the arms' platform stiffness k (their sum) and the base.
Mat2 network_compliance(const Mat3& k, const BaseCompliance& base, const Vec2& offset, const Vec2& p, const Vec2& a0) {
  // Force at G = C + offset: the wrench at C is (F, offset × F); G moves by δC + ψ·k × offset. So
  // C_G = Gᵀ·K⁻¹·G with G's columns (1, 0, −offset_y) and (0, 1, offset_x).
  const Mat3 kc = symmetric_inverse(k);
  const Vec3 gx(1.0, 0.0, -offset.y()), gy(0.0, 1.0, offset.x());
  const Vec3 kx = kc * gx, ky = kc * gy;
  const double cxy = 0.5 * (gx.dot(ky) + gy.dot(kx));
  Mat2 c;
  c << gx.dot(kx), cxy, cxy, gy.dot(ky);
  // The base frame under both arms, in series with them: translation, and rotation about the actuators'
  // midpoint A_0, which moves p by ψ·k × (p − A_0).
  const Vec2 w(a0.y() - p.y(), p.x() - a0.x());
  c(0, 0) += base.x_m_per_N;
  c(1, 1) += base.y_m_per_N;
  return c + base.rotation_rad_per_Nm * w * w.transpose();
}

Mat2 network_compliance(const Pose& pose, const std::array<detail::ArmSprings, 2>& arms, const BaseCompliance& base,
                        const Vec2& offset, const Vec2& p, const Vec2& a0) {
  return network_compliance(arm_stiffness(pose[0], arms[0]) + arm_stiffness(pose[1], arms[1]), base, offset, p, a0);
}

// The arms' poses at p (p within reach).
Pose pose_at(const kinematics::FiveBar& five_bar, const kinematics::Vec2& q, const Vec2& p) {
  const auto& g = five_bar.geometry();
  const auto elbow = five_bar.elbows(q);
  Pose pose;
  for (std::size_t i = 0; i < 2; ++i) {
    pose[i].A = g.actuator_m[i];
    pose[i].B = elbow[i];
    pose[i].lp = g.proximal_m[i];
    pose[i].ld = g.distal_m[i];
    pose[i].e = (pose[i].B - pose[i].A) / pose[i].lp;
    pose[i].u = (p - pose[i].B) / pose[i].ld;
  }
  return pose;
}

Vec2 midpoint(const kinematics::FiveBar& five_bar) {
  return 0.5 * (five_bar.geometry().actuator_m[0] + five_bar.geometry().actuator_m[1]);
}

}  // namespace

StructuralModel::StructuralModel(const kinematics::Robot& robot, std::array<ArmCompliance, 2> arms,
                                 compliance::GridBounds region, BaseCompliance base, Vec2 measured_offset_m)
    : five_bar_(robot.five_bar()), arms_(arms), base_(base), region_(region), offset_(measured_offset_m) {
  for (double v : {base.x_m_per_N, base.y_m_per_N, base.rotation_rad_per_Nm}) {
    if (!(std::isfinite(v) && v >= 0.0)) throw Error("structural model: base compliances must be finite and ≥ 0");
  }
  for (const auto& arm : arms_) {
    for (int k = 0; k < ArmCompliance::count; ++k) {
      if (!(std::isfinite(arm[k]) && arm[k] >= 0.0)) throw Error("structural model: compliances must be finite and ≥ 0");
    }
    if (!arm.proximal_bar_offset_m.allFinite() || !arm.distal_bar_offset_m.allFinite()) {
      throw Error("structural model: bar offsets must be finite");
    }
  }
  if (!offset_.allFinite()) throw Error("structural model: the measured point's offset must be finite");
  springs_ = arm_springs(arms_, five_bar_.geometry());
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
  return network_compliance(pose_at(five_bar_, inverse.q, p), springs_, base_, offset_, p, midpoint(five_bar_));
}

nlohmann::json StructuralModel::parameters() const {
  nlohmann::json arms = nlohmann::json::array();
  for (const auto& a : arms_) {
    arms.push_back({{"actuator_rad_per_Nm", a.actuator_rad_per_Nm},
                    {"proximal_bending_per_Nm2", a.proximal_bending_per_Nm2},
                    {"proximal_axial_per_N", a.proximal_axial_per_N},
                    {"distal_axial_per_N", a.distal_axial_per_N},
                    {"proximal_bar_m_per_N", a.proximal_bar_m_per_N},
                    {"distal_bar_m_per_N", a.distal_bar_m_per_N},
                    {"proximal_bar_offset_mm", {a.proximal_bar_offset_m.x() * 1e3, a.proximal_bar_offset_m.y() * 1e3}},
                    {"distal_bar_offset_mm", {a.distal_bar_offset_m.x() * 1e3, a.distal_bar_offset_m.y() * 1e3}}});
  }
  return {{"arms", arms},
          {"base", {{"x_m_per_N", base_.x_m_per_N}, {"y_m_per_N", base_.y_m_per_N},
                    {"rotation_rad_per_Nm", base_.rotation_rad_per_Nm}}},
          {"measured_offset_mm", {offset_.x() * 1e3, offset_.y() * 1e3}}};
}

namespace {

struct Cell {
  int point;  // index into the fit's points
  Vec2 force;
  double value;
  int axis;    // 0: dx, 1: dy
  int series;  // one load series: point × direction × axis
};

struct Cells {
  std::vector<Vec2> points;
  std::vector<Cell> cells;
  int series = 0;
};

Cells cells_of(const measurement::DisplacementTable& table) {
  Cells out;
  std::vector<std::string> series, points;
  const auto index = [](std::vector<std::string>& keys, const std::string& key) {
    const auto it = std::find(keys.begin(), keys.end(), key);
    if (it != keys.end()) return static_cast<int>(it - keys.begin());
    keys.push_back(key);
    return static_cast<int>(keys.size()) - 1;
  };
  for (const auto& r : table.rows) {
    const Vec2 f = r.force_N * Vec2(measurement::direction_x(r.direction), measurement::direction_y(r.direction));
    const int point = index(points, fmt::format("{}|{}", r.x_m, r.y_m));
    if (point == static_cast<int>(out.points.size())) out.points.emplace_back(r.x_m, r.y_m);
    for (int axis = 0; axis < 2; ++axis) {
      const auto& v = axis == 0 ? r.dx_m : r.dy_m;
      if (!v) continue;
      const int s = index(series, fmt::format("{}|{}|{}", r.point, measurement::to_string(r.direction), axis));
      out.cells.push_back({point, f, *v, axis, s});
    }
  }
  out.series = static_cast<int>(series.size());
  return out;
}

// Residuals C·F + n_s − d of every cell, n_s the offset of its load series (eq. 4.8's intercept: the readings
// at step 0 carry settling and hysteresis that no compliance reproduces), set to the series' mean misfit.
template <class ComplianceAt>
Eigen::VectorXd residuals(const Cells& c, ComplianceAt&& compliance_at) {
  std::vector<Mat2> at(c.points.size());
  for (std::size_t k = 0; k < c.points.size(); ++k) at[k] = compliance_at(k);
  Eigen::VectorXd r(static_cast<Eigen::Index>(c.cells.size()));
  std::vector<double> sum(static_cast<std::size_t>(c.series), 0.0), count(static_cast<std::size_t>(c.series), 0.0);
  for (std::size_t k = 0; k < c.cells.size(); ++k) {
    const Cell& e = c.cells[k];
    const double v = (at[static_cast<std::size_t>(e.point)] * e.force)(e.axis) - e.value;
    r(static_cast<Eigen::Index>(k)) = v;
    sum[static_cast<std::size_t>(e.series)] += v;
    count[static_cast<std::size_t>(e.series)] += 1.0;
  }
  for (std::size_t k = 0; k < c.cells.size(); ++k) {
    const auto s = static_cast<std::size_t>(c.cells[k].series);
    r(static_cast<Eigen::Index>(k)) -= sum[s] / count[s];
  }
  return r;
}

// The fit's parameters: per arm 6 log-compliances and 4 offsets, 3 log base compliances, the measured offset.
constexpr int kPerArm = ArmCompliance::count + 4;
constexpr int kBase = 2 * kPerArm;
constexpr int kOffset = kBase + 3;
constexpr int kParams = kOffset + 2;

// Whether parameter k is a bar offset of an arm (the only parameters the flatness guard depends on).
bool is_arm_offset(int k) { return k < kBase && k % kPerArm >= ArmCompliance::count; }

struct Unpacked {
  std::array<ArmCompliance, 2> arms;
  BaseCompliance base;
  Vec2 offset;
};

Unpacked unpack(const Eigen::VectorXd& x) {
  Unpacked u;
  for (int i = 0; i < 2; ++i) {
    auto& a = u.arms[static_cast<std::size_t>(i)];
    for (int k = 0; k < ArmCompliance::count; ++k) a[k] = std::exp(x(i * kPerArm + k));
    a.proximal_bar_offset_m = x.segment<2>(i * kPerArm + ArmCompliance::count);
    a.distal_bar_offset_m = x.segment<2>(i * kPerArm + ArmCompliance::count + 2);
  }
  u.base = {std::exp(x(kBase)), std::exp(x(kBase + 1)), std::exp(x(kBase + 2))};
  u.offset = x.segment<2>(kOffset);
  return u;
}

// The arm elements' physical floors, SI (the fit's lower bounds): no actuator of such a robot is stiffer than
// 10⁷ N·m/rad, no proximal link has EI above 10⁶ N·m² (a solid steel shaft of 10 cm), and no link, bearing or
// parallelogram bar is stiffer than 10⁹ N/m (a steel bar of 10 cm² and 0.2 m). Below them an element is rigid
// for every purpose of the tables (10⁻⁹ m/N is 0.2 µm at 200 N), and a "rigid" bar of 10⁻¹⁴ m/N against the
// bodies' free rotation (kFreeRotation) leaves the condensation with a condition number of 10²⁴: a parallelogram
// that nears flat then turns the field into a spike instead of a smooth rise.
constexpr std::array<double, ArmCompliance::count> kFloor{1e-7, 1e-6, 1e-9, 1e-9, 1e-9, 1e-9};

// Bounds: arm compliances kFloor … 100 (SI), base 1e-14 … 1, offsets within ±kStructuralMaxOffset_m.
std::pair<Eigen::VectorXd, Eigen::VectorXd> bounds() {
  Eigen::VectorXd lo(kParams), hi(kParams);
  for (int k = 0; k < kParams; ++k) {
    const bool offset = k >= kOffset || is_arm_offset(k);
    const double floor = k < kBase && !offset ? kFloor[static_cast<std::size_t>(k % kPerArm)] : 1e-14;
    lo(k) = offset ? -kStructuralMaxOffset_m : std::log(floor);
    hi(k) = offset ? kStructuralMaxOffset_m : (k >= kBase ? 0.0 : std::log(1e2));
  }
  return {lo, hi};
}

// A parallelogram must not flatten inside its workspace: at flat it is singular (it can fold into the crossed
// branch) and the body it guides loses its orientation. Soft, so that the fit can still trade a little margin
// for the table: at each point of a kGuardGrid² grid over the measured rectangle, each bar's offset that comes
// within asin(kMinSine) (17.5°) of its link costs up to kGuardWeight (30) µm (the residuals' unit) per point. The
// grid's spacing (a few mm, ≈ 2° of link rotation) is well inside that margin, so no flat pose slips between.
constexpr int kGuardGrid = 15;
constexpr double kMinSine = 0.3;
constexpr double kGuardWeight = 30.0;

double flatness(const Vec2& offset, const Vec2& link) {
  return kGuardWeight * std::max(0.0, 1.0 - std::abs(cross(offset, link)) / std::max(offset.norm(), 1e-6) / kMinSine);
}

// A deterministic, platform-independent sequence in [0, 1) (SplitMix64).
struct Sequence {
  std::uint64_t s;
  double next() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  }
};

// Start k: orders of magnitude of a small aluminium robot (actuator 1e-4 rad/N·m, 1/EI 1e-3 /N·m², bars 0.1 µm/N),
// each spread over a few decades, offsets anywhere in the bodies.
Eigen::VectorXd start(int k) {
  Sequence seq{static_cast<std::uint64_t>(k) * 7919u + 1u};
  const std::array<double, ArmCompliance::count> typical{1e-4, 1e-3, 1e-8, 1e-8, 1e-7, 1e-7};
  const std::array<double, ArmCompliance::count> spread{2, 3, 2, 2, 3, 3};
  Eigen::VectorXd x(kParams);
  for (int i = 0; i < 2; ++i) {
    for (int e = 0; e < ArmCompliance::count; ++e) {
      const auto ue = static_cast<std::size_t>(e);
      x(i * kPerArm + e) = std::log(typical[ue]) + spread[ue] * (2.0 * seq.next() - 1.0);
    }
    for (int o = 0; o < 4; ++o) x(i * kPerArm + ArmCompliance::count + o) = kStructuralMaxOffset_m * (2.0 * seq.next() - 1.0);
  }
  x(kBase) = x(kBase + 1) = std::log(1e-7);  // base: 0.1 µm/N, 10 µrad/N·m
  x(kBase + 2) = std::log(1e-5);
  x(kOffset) = 0.03 * (2.0 * seq.next() - 1.0);
  x(kOffset + 1) = 0.03 * (2.0 * seq.next() - 1.0);
  return x;
}

// Projected Levenberg–Marquardt: where it stands (x, its damping λ) and whether it has stopped, so that a
// run can be continued exactly where it left off.
struct Descent {
  Eigen::VectorXd x;
  double lambda = 1e-2;
  bool stopped = false;
};

// The parameters of arm i are x(i·kPerArm) … x(i·kPerArm + kPerArm − 1); -2 for the base's and the offset's.
int arm_of(int k) { return k < kBase ? k / kPerArm : -2; }

// The fit's residuals in two parts: the table's cells (every parameter) and the flatness guard (the arms' bar
// offsets only). For the Jacobian, `table(x, -1, &kept)` keeps each arm's platform stiffness at every table point,
// so that `table(xp, arm_of(k), &kept)` recomputes only the arm whose parameter k was changed (none for the base's
// and the offset's): the same numbers as a full evaluation, with fewer arms to condense.
template <class Table, class Guard>
struct SplitCost {
  Table table;  // table(x, arm_to_evaluate, kept) → residuals; kept: the other arm's stiffnesses or nullptr
  Guard guard;
  Eigen::VectorXd operator()(const Eigen::VectorXd& x) const {
    const Eigen::VectorXd t = table(x, -1, nullptr), g = guard(x);
    Eigen::VectorXd r(t.size() + g.size());
    r << t, g;
    return r;
  }
};

// Continues `d` by up to `iterations` steps.
template <class Cost>
void descend(Descent& d, const Cost& cost, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, int iterations) {
  Eigen::VectorXd& x = d.x;
  double& lambda = d.lambda;
  x = x.cwiseMax(lo).cwiseMin(hi);
  Eigen::VectorXd r = cost(x);
  std::array<std::vector<Mat3>, 2> kept;  // each arm's stiffness at the table's points, at x
  const Eigen::Index table_rows = r.size() - cost.guard(x).size();
  Eigen::MatrixXd J(r.size(), kParams);
  for (int it = 0; it < iterations && !d.stopped; ++it) {
    const Eigen::VectorXd rt = r.head(table_rows), rg = r.tail(r.size() - table_rows);
    cost.table(x, -1, &kept);
    for (int k = 0; k < kParams; ++k) {
      Eigen::VectorXd xp = x;
      const double h = k >= kOffset || is_arm_offset(k) ? 1e-6 : 1e-5;
      xp(k) += h;
      J.col(k).head(table_rows) = (cost.table(xp, arm_of(k), &kept) - rt) / h;
      // The guard depends on the bar offsets alone: its other columns are exactly the zeros that differencing
      // it would give.
      if (is_arm_offset(k)) {
        J.col(k).tail(rg.size()) = (cost.guard(xp) - rg) / h;
      } else {
        J.col(k).tail(rg.size()).setZero();
      }
    }
    const Eigen::MatrixXd A = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      Eigen::MatrixXd Ad = A;
      Ad.diagonal() += lambda * (A.diagonal().array() + 1e-30).matrix();
      const Eigen::VectorXd xn = (x - Ad.ldlt().solve(g)).cwiseMax(lo).cwiseMin(hi);
      const Eigen::VectorXd rn = cost(xn);
      if (rn.squaredNorm() < r.squaredNorm()) {
        improved = (r.squaredNorm() - rn.squaredNorm()) > 1e-10 * r.squaredNorm();
        x = xn;
        r = rn;
        lambda = std::max(lambda / 3.0, 1e-9);
        if (!improved) break;
      } else {
        lambda *= 4.0;
      }
    }
    if (!improved) d.stopped = true;
  }
}

constexpr int kStarts = 16;     // the fit keeps the best of these fixed starts …
constexpr int kScreenSteps = 40;  // … after screening all of them for this many steps
constexpr int kFinalists = 4;     // and carrying the best few on
constexpr int kSteps = 300;       // to this many steps in all

}  // namespace

StructuralFitReport structural_fit_report(const compliance::Model& model, const measurement::DisplacementTable& table) {
  const Cells c = cells_of(table);
  StructuralFitReport rep;
  rep.cells = static_cast<int>(c.cells.size());
  if (rep.cells == 0) return rep;
  const Eigen::VectorXd r = residuals(c, [&](std::size_t k) { return model.compliance(c.points[k]); });
  rep.max_error_m = r.cwiseAbs().maxCoeff();
  rep.rms_error_m = std::sqrt(r.squaredNorm() / rep.cells);
  rep.within_23um = static_cast<int>((r.cwiseAbs().array() <= 23e-6).count());
  return rep;
}

std::shared_ptr<StructuralModel> fit_structural_model(const kinematics::Robot& robot,
                                                      const measurement::DisplacementTable& table,
                                                      StructuralFitReport* report) {
  const Cells c = cells_of(table);
  if (c.cells.size() < static_cast<std::size_t>(kParams)) {
    throw Error(SourceLocation{table.source}, "structural model: the table has too few translations (dx, dy) to fit");
  }
  const compliance::GridBounds region = compliance::table_region(table);
  const kinematics::FiveBar five_bar = robot.five_bar();
  // The poses at the table's points do not depend on the parameters: solve them once.
  std::vector<Pose> poses;
  for (const Vec2& p : c.points) {
    const auto inverse = five_bar.solve_inverse(p);
    if (inverse.status != kinematics::Reach::ok) {
      throw Error(SourceLocation{table.source},
                  fmt::format("structural model: the point ({:.3f}, {:.3f}) mm is out of the robot's reach", p.x() * 1e3,
                              p.y() * 1e3));
    }
    poses.push_back(pose_at(five_bar, inverse.q, p));
  }
  std::vector<Pose> guard;
  for (int i = 0; i < kGuardGrid; ++i) {
    for (int j = 0; j < kGuardGrid; ++j) {
      const Vec2 p(region.x_min + (region.x_max - region.x_min) * i / (kGuardGrid - 1.0),
                   region.y_min + (region.y_max - region.y_min) * j / (kGuardGrid - 1.0));
      const auto inverse = five_bar.solve_inverse(p);
      if (inverse.status == kinematics::Reach::ok) guard.push_back(pose_at(five_bar, inverse.q, p));
    }
  }
  const Vec2 a0 = midpoint(five_bar);
  const auto& geometry = five_bar.geometry();
  // arm = -1 and kept = nullptr: a full evaluation; arm = -1 with kept: the same, filling kept with both arms'
  // stiffnesses; arm = 0 or 1 with kept: that arm evaluated, the other read from kept; arm = -2 (the base's and
  // the offset's parameters) with kept: both arms read from kept.
  auto table_cost = [&](const Eigen::VectorXd& x, int arm, std::array<std::vector<Mat3>, 2>* kept) -> Eigen::VectorXd {
    const Unpacked u = unpack(x);
    const auto springs = arm_springs(u.arms, geometry);
    const bool fill = kept && arm == -1;
    if (fill) {
      for (auto& v : *kept) v.resize(poses.size());
    }
    return 1e6 * residuals(c, [&](std::size_t k) {
      Mat3 s[2];
      for (int i = 0; i < 2; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const bool reuse = kept && !fill && arm != i;
        s[i] = reuse ? (*kept)[ui][k] : arm_stiffness(poses[k][ui], springs[ui]);
        if (fill) (*kept)[ui][k] = s[i];
      }
      return network_compliance(s[0] + s[1], u.base, u.offset, c.points[k], a0);
    });
  };
  auto guard_cost = [&](const Eigen::VectorXd& x) {
    const Unpacked u = unpack(x);
    Eigen::VectorXd r(static_cast<Eigen::Index>(4 * guard.size()));
    Eigen::Index k = 0;
    for (const Pose& g : guard) {
      for (std::size_t i = 0; i < 2; ++i) {
        r(k++) = flatness(u.arms[i].proximal_bar_offset_m, g[i].e);
        r(k++) = flatness(u.arms[i].distal_bar_offset_m, g[i].u);
      }
    }
    return r;
  };
  const SplitCost<decltype(table_cost), decltype(guard_cost)> cost{table_cost, guard_cost};
  const auto [lo, hi] = bounds();
  // Every start descends a little; the most promising go on, each exactly as an uninterrupted run would (a
  // start stopped by then is already final). For both thesis robots the winner of all 16 run to the end
  // (start 13, by far) is among the best 4 after 40 steps. Ties keep the lower start.
  std::vector<std::pair<double, Descent>> runs;
  for (int k = 0; k < kStarts; ++k) {
    Descent d{start(k)};
    descend(d, cost, lo, hi, kScreenSteps);
    runs.emplace_back(cost(d.x).squaredNorm(), std::move(d));
  }
  std::stable_sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  runs.resize(kFinalists);
  for (auto& [value, d] : runs) {
    descend(d, cost, lo, hi, kSteps - kScreenSteps);
    value = cost(d.x).squaredNorm();
  }
  const auto best = std::min_element(runs.begin(), runs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const Unpacked u = unpack(best->second.x);
  auto model = std::make_shared<StructuralModel>(robot, u.arms, region, u.base, u.offset);
  if (report) *report = structural_fit_report(*model, table);
  return model;
}

}  // namespace stiffpath::simulation
