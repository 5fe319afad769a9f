// Fitting the structural C_true to the robot's measured translations (Levenberg–Marquardt from fixed starts).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>
#include <fmt/format.h>

#include "stiffpath/compliance/model_factory.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/least_squares.hpp"
#include "stiffpath/simulation/structural_compliance.hpp"
#include "structural_network.hpp"

namespace stiffpath::simulation {

using network::arm_springs;
using network::arm_stiffness;
using network::cross;
using network::Mat2;
using network::Mat3;
using network::midpoint;
using network::network_compliance;
using network::Pose;
using network::pose_at;
using network::Vec2;

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

// A table point by its exact position (rows of one point share it bit for bit), and a load series by its point,
// direction and axis; each numbered in order of first appearance.
using PointKey = std::pair<double, double>;
using SeriesKey = std::tuple<std::string, measurement::ForceDirection, int>;

template <class Key>
int index_of(std::map<Key, int>& keys, const Key& key) {
  return keys.try_emplace(key, static_cast<int>(keys.size())).first->second;
}

Cells cells_of(const measurement::DisplacementTable& table) {
  Cells out;
  std::map<PointKey, int> points;
  std::map<SeriesKey, int> series;
  for (const auto& r : table.rows) {
    const Vec2 f = r.force_N * Vec2(measurement::direction_x(r.direction), measurement::direction_y(r.direction));
    const int point = index_of(points, PointKey{r.x_m, r.y_m});
    if (point == static_cast<int>(out.points.size())) out.points.emplace_back(r.x_m, r.y_m);
    for (int axis = 0; axis < 2; ++axis) {
      const auto& v = axis == 0 ? r.dx_m : r.dy_m;
      if (!v) continue;
      out.cells.push_back({point, f, *v, axis, index_of(series, SeriesKey{r.point, r.direction, axis})});
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

// The parameters of arm i are x(i·kPerArm) … x(i·kPerArm + kPerArm − 1); -2 for the base's and the offset's.
int arm_of(int k) { return k < kBase ? k / kPerArm : -2; }

// Forward-difference steps of the Jacobian: on the compliances' logarithms and on the offsets (m).
constexpr double kLogStep = 1e-5;
constexpr double kOffsetStep = 1e-6;

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
  // ∂r/∂x by forward differences, given r(x).
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& r) const {
    std::array<std::vector<Mat3>, 2> kept;  // each arm's stiffness at the table's points, at x
    const Eigen::Index guard_rows = guard(x).size(), table_rows = r.size() - guard_rows;
    const Eigen::VectorXd rt = r.head(table_rows), rg = r.tail(guard_rows);
    Eigen::MatrixXd J(r.size(), kParams);
    table(x, -1, &kept);
    for (int k = 0; k < kParams; ++k) {
      Eigen::VectorXd xp = x;
      const double h = k >= kOffset || is_arm_offset(k) ? kOffsetStep : kLogStep;
      xp(k) += h;
      J.col(k).head(table_rows) = (table(xp, arm_of(k), &kept) - rt) / h;
      // The guard depends on the bar offsets alone: its other columns are exactly the zeros that differencing
      // it would give.
      if (is_arm_offset(k)) {
        J.col(k).tail(guard_rows) = (guard(xp) - rg) / h;
      } else {
        J.col(k).tail(guard_rows).setZero();
      }
    }
    return J;
  }
};

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
  core::LeastSquaresProblem problem;
  problem.residuals = [&](const Eigen::VectorXd& x) { return cost(x); };
  problem.jacobian = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& r) { return cost.jacobian(x, r); };
  problem.lower = lo;
  problem.upper = hi;
  // The solver's settings are core::LeastSquaresSettings' defaults (Marquardt's damping from 10⁻², ÷3 after a step
  // that lowers the cost, ×4 after one that does not, converged below a 10⁻¹⁰ relative decrease).
  // Every start descends a little; the most promising go on, each exactly as an uninterrupted run would (a
  // start stopped by then is already final). For both thesis robots the winner of all 16 run to the end
  // (start 13, by far) is among the best 4 after 40 steps. Ties keep the lower start.
  std::vector<core::LevenbergMarquardt> runs;
  for (int k = 0; k < kStarts; ++k) {
    runs.emplace_back(problem, start(k));
    runs.back().run(kScreenSteps);
  }
  const auto by_cost = [](const core::LevenbergMarquardt& a, const core::LevenbergMarquardt& b) { return a.cost() < b.cost(); };
  std::stable_sort(runs.begin(), runs.end(), by_cost);
  runs.erase(runs.begin() + kFinalists, runs.end());
  for (auto& run : runs) run.run(kSteps - kScreenSteps);
  const auto best = std::min_element(runs.begin(), runs.end(), by_cost);
  const Unpacked u = unpack(best->x());
  auto model = std::make_shared<StructuralModel>(robot, u.arms, region, u.base, u.offset);
  if (report) *report = structural_fit_report(*model, table);
  return model;
}

}  // namespace stiffpath::simulation
