// Compliance campaign design: I-optimal for the physical model plus space-filling for its residual spline, over a usable rectangle.
#include "stiffpath/calibration/campaign_plan.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/compliance/uncertainty.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::calibration {

namespace {
using kinematics::Vec2;
using compliance::GridBounds;
using compliance::Mat2;

// The criterion is averaged over an evaluation lattice of this many points per side of the region.
constexpr int kEvaluationLattice = 15;
// The physical model the plan is for: order 1 (physical, and physical-spline's physical part).
constexpr int kOrder = 1;
constexpr int kTerms = 3;
constexpr int kUnknowns = 3 * kTerms;

bool usable(const kinematics::Robot& robot, const kinematics::FiveBar& five_bar, const Vec2& p, double max_condition) {
  if (!robot.refusal(p).empty()) return false;
  return five_bar.condition_number(robot.inverse(p)) <= max_condition;
}

// Rᵀ·E_m·R for the three symmetric unit matrices E_m of D, R = U⁻¹ (fit_physical_model's design).
std::array<Mat2, 3> link_terms(const kinematics::FiveBarGeometry& g, const Vec2& p) {
  const Mat2 r = compliance::PhysicalModel::link_force_map(g, p);
  const Mat2 e[3] = {(Mat2() << 1, 0, 0, 0).finished(), (Mat2() << 0, 1, 1, 0).finished(),
                     (Mat2() << 0, 0, 0, 1).finished()};
  return {r.transpose() * e[0] * r, r.transpose() * e[1] * r, r.transpose() * e[2] * r};
}

// Design rows (µm/N parameters, m of deflection) of every cell a point gives: per direction, loaded step, axis.
Eigen::MatrixXd cell_rows(const kinematics::FiveBarGeometry& g, const GridBounds& region, const Vec2& p,
                          const std::vector<double>& loads, const std::vector<measurement::ForceDirection>& directions) {
  std::array<double, compliance::PhysicalModel::kMaxTerms> b{};
  compliance::PhysicalModel::basis(region, kOrder, p, b);
  const auto terms = link_terms(g, p);
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(2 * loads.size() * directions.size()), kUnknowns);
  Eigen::Index row = 0;
  for (const auto d : directions) {
    for (const double f : loads) {
      const Vec2 F = f * Vec2(measurement::direction_x(d), measurement::direction_y(d));
      for (int axis = 0; axis < 2; ++axis) {
        for (int k = 0; k < kTerms; ++k) {
          for (int m = 0; m < 3; ++m) rows(row, 3 * k + m) = (terms[static_cast<std::size_t>(m)] * F)(axis) * b[static_cast<std::size_t>(k)] * 1e-6;
        }
        ++row;
      }
    }
  }
  return rows;
}

// Rows mapping the parameters to C's entries c11, c12, c22 at q (µm/N parameters → m/N).
Eigen::Matrix<double, 3, kUnknowns> entry_rows(const kinematics::FiveBarGeometry& g, const GridBounds& region, const Vec2& q) {
  std::array<double, compliance::PhysicalModel::kMaxTerms> b{};
  compliance::PhysicalModel::basis(region, kOrder, q, b);
  const auto terms = link_terms(g, q);
  Eigen::Matrix<double, 3, kUnknowns> G;
  for (int k = 0; k < kTerms; ++k) {
    for (int m = 0; m < 3; ++m) {
      const Mat2& t = terms[static_cast<std::size_t>(m)];
      const double s = b[static_cast<std::size_t>(k)] * 1e-6;
      G(0, 3 * k + m) = t(0, 0) * s;
      G(1, 3 * k + m) = t(0, 1) * s;
      G(2, 3 * k + m) = t(1, 1) * s;
    }
  }
  return G;
}

struct Evaluator {
  const kinematics::Robot& robot;
  GridBounds region;
  std::vector<double> loads;
  std::vector<measurement::ForceDirection> directions;
  double sigma;
  std::vector<Vec2> lattice;  // where the criterion is averaged
  std::vector<Eigen::Matrix<double, 3, kUnknowns>> G;

  Evaluator(const kinematics::Robot& r, const GridBounds& reg, std::vector<double> l, std::vector<measurement::ForceDirection> d,
            double s)
      : robot(r), region(reg), loads(std::move(l)), directions(std::move(d)), sigma(s) {
    for (int i = 0; i < kEvaluationLattice; ++i) {
      for (int j = 0; j < kEvaluationLattice; ++j) {
        const Vec2 q(region.x_min + (region.x_max - region.x_min) * i / (kEvaluationLattice - 1.0),
                     region.y_min + (region.y_max - region.y_min) * j / (kEvaluationLattice - 1.0));
        lattice.push_back(q);
        G.push_back(entry_rows(robot.geometry, region, q));
      }
    }
  }
  Eigen::MatrixXd information(const Vec2& p) const {
    const Eigen::MatrixXd a = cell_rows(robot.geometry, region, p, loads, directions);
    return a.transpose() * a / (sigma * sigma);
  }
  // Mean prediction variance of C's entries over the lattice, given the information M.
  double physical(const Eigen::MatrixXd& M) const {
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
    double sum = 0.0;
    for (const auto& g : G) sum += (g * ldlt.solve(g.transpose())).trace();
    return sum / static_cast<double>(G.size());
  }
  double interpolation(const std::vector<Vec2>& points) const {
    const compliance::InterpolationVariance v(points, compliance::kUncertaintySmoothing);
    double sum = 0.0;
    for (const auto& q : lattice) sum += v.at(q);
    return sum / static_cast<double>(lattice.size());
  }
  std::pair<double, double> both(const std::vector<Vec2>& points) const {
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(kUnknowns, kUnknowns);
    for (const auto& p : points) M += information(p);
    return {physical(M), interpolation(points)};
  }
};

// The loaded steps: the largest candidate, then those that most increase Σ(F − F̄)² over {0} ∪ chosen.
std::vector<double> choose_loads(std::vector<double> candidates, int count) {
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  if (static_cast<int>(candidates.size()) < count) {
    throw Error(fmt::format("campaign plan: {} loaded steps asked for, but only {} distinct loads are available", count,
                            candidates.size()));
  }
  std::vector<double> chosen{candidates.back()};
  candidates.pop_back();
  const auto spread = [](const std::vector<double>& f) {
    double mean = 0.0;
    for (const double v : f) mean += v / static_cast<double>(f.size() + 1);  // with step 0's F = 0
    double ss = mean * mean;
    for (const double v : f) ss += (v - mean) * (v - mean);
    return ss;
  };
  while (static_cast<int>(chosen.size()) < count) {
    std::size_t best = 0;
    double best_ss = -1.0;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
      auto trial = chosen;
      trial.push_back(candidates[k]);
      const double ss = spread(trial);
      if (ss > best_ss) {
        best_ss = ss;
        best = k;
      }
    }
    chosen.push_back(candidates[best]);
    candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(best));
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

// The regular nx × ny grid of (about) n points whose shape is nearest the region's.
std::pair<int, int> grid_shape(int n, const GridBounds& region) {
  const double aspect = (region.x_max - region.x_min) / (region.y_max - region.y_min);
  std::pair<int, int> best{2, 2};
  double best_score = 1e300;
  for (int nx = 2; nx <= n / 2; ++nx) {
    for (int ny = 2; nx * ny <= n; ++ny) {
      // Fewest points left out first, then the shape nearest the region's.
      const double score = (n - nx * ny) * 10.0 + std::abs(std::log((nx - 1.0) / (ny - 1.0) / aspect));
      if (score < best_score) {
        best_score = score;
        best = {nx, ny};
      }
    }
  }
  return best;
}

std::vector<Vec2> grid_points(int nx, int ny, const GridBounds& r) {
  std::vector<Vec2> out;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      out.emplace_back(r.x_min + (r.x_max - r.x_min) * i / (nx - 1.0), r.y_min + (r.y_max - r.y_min) * j / (ny - 1.0));
    }
  }
  return out;
}
}  // namespace

GridBounds largest_usable_rectangle(const kinematics::Robot& robot, double max_condition_number, int cells) {
  const auto& g = robot.geometry;
  auto box = GridBounds::none();
  for (int i = 0; i < 2; ++i) {
    const double reach = g.proximal_m[i] + g.distal_m[i];
    box.include(g.actuator_m[i] + Vec2(reach, reach));
    box.include(g.actuator_m[i] - Vec2(reach, reach));
  }
  const double step = std::sqrt((box.x_max - box.x_min) * (box.y_max - box.y_min) / std::max(cells, 100));
  const int nx = static_cast<int>((box.x_max - box.x_min) / step) + 1, ny = static_cast<int>((box.y_max - box.y_min) / step) + 1;
  const kinematics::FiveBar five_bar = robot.five_bar();
  const double limit = std::min(max_condition_number, robot.margin.max_condition_number);
  std::vector<std::vector<bool>> ok(static_cast<std::size_t>(nx), std::vector<bool>(static_cast<std::size_t>(ny)));
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) ok[i][j] = usable(robot, five_bar, Vec2(box.x_min + i * step, box.y_min + j * step), limit);
  }
  // The largest all-usable rectangle of lattice points: for each row j, the run heights h[i] of usable points
  // ending at j, and the largest rectangle under that histogram (a stack of increasing heights).
  std::vector<int> h(static_cast<std::size_t>(nx), 0);
  double best_area = -1.0;
  GridBounds best{};
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) h[i] = ok[i][j] ? h[i] + 1 : 0;
    std::vector<int> stack;
    for (int i = 0; i <= nx; ++i) {
      const int height = i < nx ? h[i] : 0;
      while (!stack.empty() && h[stack.back()] >= height) {
        const int top = stack.back();
        stack.pop_back();
        const int left = stack.empty() ? 0 : stack.back() + 1;
        const int width = i - left, tall = h[top];
        // Lattice points left … i−1 by j−tall+1 … j: the rectangle between them.
        const double area = (width - 1.0) * (tall - 1.0);
        if (tall >= 2 && width >= 2 && area > best_area) {
          best_area = area;
          best = {box.x_min + left * step, box.x_min + (i - 1) * step, box.y_min + (j - tall + 1) * step, box.y_min + j * step};
        }
      }
      stack.push_back(i);
    }
  }
  if (best_area <= 0.0) throw Error(fmt::format("robot {}: no usable rectangle (condition number <= {:g})", robot.name, limit));
  // Between the lattice points the boundary may dip inwards: shrink until the edges are usable at a finer step.
  for (int shrink = 0; shrink < 20; ++shrink) {
    bool edges_ok = true;
    for (int k = 0; k <= 40 && edges_ok; ++k) {
      const double t = k / 40.0;
      for (const Vec2& p : {Vec2(best.x_min + t * (best.x_max - best.x_min), best.y_min),
                            Vec2(best.x_min + t * (best.x_max - best.x_min), best.y_max),
                            Vec2(best.x_min, best.y_min + t * (best.y_max - best.y_min)),
                            Vec2(best.x_max, best.y_min + t * (best.y_max - best.y_min))}) {
        edges_ok = edges_ok && usable(robot, five_bar, p, limit);
      }
    }
    if (edges_ok) return best;
    best = best.grown(-0.25 * step);
  }
  throw Error(fmt::format("robot {}: the usable region is too ragged for a rectangle", robot.name));
}

std::pair<double, double> campaign_criterion(const kinematics::Robot& robot, const GridBounds& region,
                                             const std::vector<Vec2>& points, const CampaignPlan& plan, double cell_sigma_m) {
  return Evaluator(robot, region, plan.loads_N, plan.directions, cell_sigma_m).both(points);
}

CampaignPlan plan_campaign(const kinematics::Robot& robot, const CampaignPlanSettings& s) {
  if (s.points < 4 || s.points > kMaxCampaignPoints) {
    throw Error(fmt::format("campaign plan: the number of points must lie in [4, {}], got {}", kMaxCampaignPoints, s.points));
  }
  if (s.load_steps < 2) throw Error("campaign plan: each series needs at least 2 loaded steps (eq. 4.8's line)");
  if (s.directions.empty()) throw Error("campaign plan: no load directions");
  if (!(s.cell_sigma_m > 0.0)) throw Error("campaign plan: the measurement noise must be positive");
  for (const double f : s.candidate_loads_N) {
    if (!(f > 0.0 && f <= 1e5)) throw Error(fmt::format("campaign plan: a load must lie in (0, 1e5] N, got {}", f));
  }
  CampaignPlan plan;
  plan.region = s.region ? *s.region : largest_usable_rectangle(robot, s.max_condition_number);
  const GridBounds& r = plan.region;
  const kinematics::FiveBar five_bar = robot.five_bar();
  for (const Vec2& c : {Vec2(r.x_min, r.y_min), Vec2(r.x_max, r.y_min), Vec2(r.x_min, r.y_max), Vec2(r.x_max, r.y_max)}) {
    if (!robot.refusal(c).empty()) {
      throw Error(fmt::format("campaign plan: the region's corner ({:.3f}, {:.3f}) mm is refused: {}", c.x() * 1e3,
                              c.y() * 1e3, robot.refusal(c)));
    }
  }
  plan.loads_N = choose_loads(s.candidate_loads_N, s.load_steps);
  plan.directions = s.directions;
  plan.step0_kgf = s.step0_kgf;
  const Evaluator eval(robot, r, plan.loads_N, plan.directions, s.cell_sigma_m);
  // Candidates: a lattice over the region, those the robot reaches.
  std::vector<Vec2> candidates;
  for (int i = 0; i < s.candidate_lattice; ++i) {
    for (int j = 0; j < s.candidate_lattice; ++j) {
      const Vec2 p(r.x_min + (r.x_max - r.x_min) * i / (s.candidate_lattice - 1.0),
                   r.y_min + (r.y_max - r.y_min) * j / (s.candidate_lattice - 1.0));
      if (robot.refusal(p).empty()) candidates.push_back(p);
    }
  }
  std::vector<Eigen::MatrixXd> info;
  for (const auto& p : candidates) info.push_back(eval.information(p));
  // The reference: a regular grid of about as many points.
  const auto [nx, ny] = grid_shape(s.points, r);
  plan.grid_nx = nx;
  plan.grid_ny = ny;
  const auto [grid_phys, grid_interp] = eval.both(grid_points(nx, ny, r));
  if (s.regular_grid) {
    plan.points = grid_points(nx, ny, r);
    for (const auto& p : plan.points) {
      if (!robot.refusal(p).empty()) throw Error(fmt::format("campaign plan: the grid point ({:.3f}, {:.3f}) mm is refused: {}", p.x() * 1e3, p.y() * 1e3, robot.refusal(p)));
    }
    plan.physical_ratio = plan.interpolation_ratio = 1.0;
    return plan;
  }
  const auto score = [&](const std::vector<std::size_t>& chosen) {
    Eigen::MatrixXd M = 1e-12 * Eigen::MatrixXd::Identity(kUnknowns, kUnknowns);  // the first picks may not determine all
    std::vector<Vec2> pts;
    for (const auto c : chosen) {
      M += info[c];
      pts.push_back(candidates[c]);
    }
    return eval.physical(M) / grid_phys + eval.interpolation(pts) / grid_interp;
  };
  // The corners first (the model's rectangle is the points'), then greedily the candidate that lowers the score most.
  std::vector<std::size_t> chosen;
  for (const Vec2& c : {Vec2(r.x_min, r.y_min), Vec2(r.x_max, r.y_min), Vec2(r.x_min, r.y_max), Vec2(r.x_max, r.y_max)}) {
    std::size_t nearest = 0;
    for (std::size_t k = 1; k < candidates.size(); ++k) {
      if ((candidates[k] - c).norm() < (candidates[nearest] - c).norm()) nearest = k;
    }
    chosen.push_back(nearest);
  }
  const auto taken = [&](std::size_t c, const std::vector<std::size_t>& set) { return std::find(set.begin(), set.end(), c) != set.end(); };
  while (static_cast<int>(chosen.size()) < s.points) {
    std::size_t best = candidates.size();
    double best_score = 1e300;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      if (taken(c, chosen)) continue;
      auto trial = chosen;
      trial.push_back(c);
      const double v = score(trial);
      if (v < best_score) {
        best_score = v;
        best = c;
      }
    }
    if (best == candidates.size()) throw Error("campaign plan: the region has fewer reachable candidates than points");
    chosen.push_back(best);
  }
  for (int pass = 0; pass < s.exchange_passes; ++pass) {
    bool swapped = false;
    for (std::size_t k = 4; k < chosen.size(); ++k) {
      double best_score = score(chosen);
      for (std::size_t c = 0; c < candidates.size(); ++c) {
        if (taken(c, chosen)) continue;
        auto trial = chosen;
        trial[k] = c;
        const double v = score(trial);
        if (v < best_score - 1e-12) {
          best_score = v;
          chosen = trial;
          swapped = true;
        }
      }
    }
    if (!swapped) break;
  }
  for (const auto c : chosen) plan.points.push_back(candidates[c]);
  const auto [phys, interp] = eval.both(plan.points);
  plan.physical_ratio = phys / grid_phys;
  plan.interpolation_ratio = interp / grid_interp;
  return plan;
}

std::vector<CampaignMapPoint> campaign_map(const kinematics::Robot& robot, const CampaignPlan& plan, double cell_sigma_m, int n) {
  const GridBounds& r = plan.region;
  const Evaluator eval(robot, r, plan.loads_N, plan.directions, cell_sigma_m);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(kUnknowns, kUnknowns);
  for (const auto& p : plan.points) M += eval.information(p);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
  const compliance::InterpolationVariance v(plan.points, compliance::kUncertaintySmoothing);
  const double grid_mean = eval.interpolation(grid_points(plan.grid_nx, plan.grid_ny, r));
  const double f = plan.loads_N.back();
  std::vector<CampaignMapPoint> out;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vec2 q(r.x_min + (r.x_max - r.x_min) * i / (n - 1.0), r.y_min + (r.y_max - r.y_min) * j / (n - 1.0));
      const auto G = entry_rows(robot.geometry, r, q);
      const Eigen::Matrix3d cov = G * ldlt.solve(G.transpose());  // c11, c12, c22
      // Under F along x: Δ = F·(c11, c12); along y: F·(c12, c22).
      const double var = f * f * (cov(0, 0) + 2.0 * cov(1, 1) + cov(2, 2)) / 2.0;
      out.push_back({q, std::sqrt(std::max(var, 0.0)), grid_mean > 0.0 ? v.at(q) / grid_mean : 0.0});
    }
  }
  return out;
}

std::vector<Vec2> usable_lattice(const kinematics::Robot& robot, double max_condition_number, int cells) {
  const auto& g = robot.geometry;
  auto box = GridBounds::none();
  for (int i = 0; i < 2; ++i) {
    const double reach = g.proximal_m[i] + g.distal_m[i];
    box.include(g.actuator_m[i] + Vec2(reach, reach));
    box.include(g.actuator_m[i] - Vec2(reach, reach));
  }
  const double step = std::sqrt((box.x_max - box.x_min) * (box.y_max - box.y_min) / std::max(cells, 100));
  const kinematics::FiveBar five_bar = robot.five_bar();
  const double limit = std::min(max_condition_number, robot.margin.max_condition_number);
  std::vector<Vec2> out;
  for (double x = box.x_min; x <= box.x_max; x += step) {
    for (double y = box.y_min; y <= box.y_max; y += step) {
      if (usable(robot, five_bar, Vec2(x, y), limit)) out.emplace_back(x, y);
    }
  }
  return out;
}

measurement::DisplacementTable plan_rows(const CampaignPlan& plan) {
  measurement::DisplacementTable t;
  t.source = "campaign plan";
  int n = 0;
  for (const Vec2& p : plan.points) {
    const std::string id = fmt::format("c{}", ++n);
    for (const auto d : plan.directions) {
      int step = 0;
      for (const double f : plan.loads_N) {
        measurement::DisplacementRow row;
        row.direction = d;
        row.point = id;
        row.x_m = p.x();
        row.y_m = p.y();
        row.step = ++step;
        row.force_N = row.nominal_force_N = f;
        row.force_kgf = plan.step0_kgf + f / units::standard_gravity_m_s2;
        t.rows.push_back(row);
      }
    }
  }
  return t;
}

void save_campaign_plan(const CampaignPlan& plan, const std::string& path) {
  core::AtomicFile file(path);
  auto& out = file.stream();
  out << fmt::format("# campaign plan: step 0 (the reference) of every series carries {:.6f} kgf\n", plan.step0_kgf);
  out << "point,x_mm,y_mm,direction,step,force_kgf,F_N\n";
  for (const auto& r : plan_rows(plan).rows) {
    out << fmt::format("{},{:.4f},{:.4f},{},{},{:.6f},{:.4f}\n", r.point, r.x_m * 1e3, r.y_m * 1e3,
                       measurement::to_string(r.direction), r.step, r.force_kgf, r.force_N);
  }
  file.commit();
}

measurement::DisplacementTable load_campaign_plan(const std::string& path) {
  // A plan is a displacement table without its displacements: read it as one with empty cells.
  core::CsvReader csv(path);
  const int header_line = csv.line();
  for (const char* name : {"point", "x_mm", "y_mm", "direction", "step", "force_kgf", "F_N"}) {
    if (!csv.find_column(name)) {
      throw Error(SourceLocation{path, header_line, 1},
                  fmt::format("missing column '{}' (a campaign plan has point,x_mm,y_mm,direction,step,force_kgf,F_N)", name));
    }
  }
  std::string text = "point,x_mm,y_mm,direction,step,force_kgf,F_N,dx_mm,dy_mm\n";
  const auto c = [&](const char* name) { return *csv.find_column(name); };
  std::vector<int> lines;
  while (csv.next()) {
    text += fmt::format("{},{},{},{},{},{},{},,\n", csv.text(c("point")), csv.text(c("x_mm")), csv.text(c("y_mm")),
                        csv.text(c("direction")), csv.text(c("step")), csv.text(c("force_kgf")), csv.text(c("F_N")));
    lines.push_back(csv.line());
  }
  measurement::DisplacementTable t;
  try {
    t = measurement::parse_displacement_table(text, path);
  } catch (const Error& e) {
    // Name the plan's own line (the text above has one header line and no comments).
    const int line = e.where().line >= 2 && e.where().line - 2 < static_cast<int>(lines.size()) ? lines[static_cast<std::size_t>(e.where().line - 2)] : e.where().line;
    throw Error(SourceLocation{path, line, 0}, e.message());
  }
  t.source = path;
  if (t.rows.empty()) throw Error(SourceLocation{path, header_line, 1}, "the campaign plan has no rows");
  return t;
}

measurement::DisplacementTable truth_from_field(const measurement::DisplacementTable& plan, const compliance::Model& field) {
  measurement::DisplacementTable t = plan;
  t.source = "field at " + plan.source;
  for (auto& r : t.rows) {
    const Vec2 F = r.force_N * Vec2(measurement::direction_x(r.direction), measurement::direction_y(r.direction));
    const Vec2 d = field.compliance(Vec2(r.x_m, r.y_m)) * F;
    r.dx_m = d.x();
    r.dy_m = d.y();
    r.dz_m = 0.0;
    r.rx_rad = 0.0;
    r.ry_rad = 0.0;
  }
  return t;
}

}  // namespace stiffpath::calibration
