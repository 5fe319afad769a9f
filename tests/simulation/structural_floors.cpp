// Floors of the thesis's translation tables by linear least squares (per series, symmetric per point, rotation-invariant).
#include "structural_floors.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

namespace stiffpath::simulation::testing {
namespace {

struct Obs {
  std::string point, direction;
  int axis;
  double x_m, y_m, fx, fy, force_N, value;
  int series;
};

std::vector<Obs> observations(const measurement::DisplacementTable& table) {
  std::vector<Obs> out;
  std::map<std::string, int> series;
  for (const auto& r : table.rows) {
    const double fx = r.force_N * measurement::direction_x(r.direction),
                 fy = r.force_N * measurement::direction_y(r.direction);
    for (int axis = 0; axis < 2; ++axis) {
      const auto& v = axis == 0 ? r.dx_m : r.dy_m;
      if (!v) continue;
      const std::string key = r.point + measurement::to_string(r.direction) + std::to_string(axis);
      const int s = series.emplace(key, static_cast<int>(series.size())).first->second;
      out.push_back({r.point, measurement::to_string(r.direction), axis, r.x_m, r.y_m, fx, fy, r.force_N, *v, s});
    }
  }
  return out;
}

// Least squares of A·θ = b over the rows `rows` of obs; the residuals go into the floor.
void solve_into(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const std::vector<const Obs*>& rows, Floor& f) {
  const Eigen::VectorXd theta = A.completeOrthogonalDecomposition().solve(b);
  const Eigen::VectorXd r = b - A * theta;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    f.cells.push_back({rows[k]->point, rows[k]->direction, rows[k]->axis, rows[k]->force_N, r(static_cast<Eigen::Index>(k))});
  }
}

// Columns of the symmetric compliance's entries (xx, xy, yy) for one observation: (C·F)_axis after rotating by phi.
std::array<double, 3> symmetric_columns(const Obs& o, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  const Eigen::Vector2d f(o.fx, o.fy);
  std::array<double, 3> out{};
  const Eigen::Matrix2d E[3] = {(Eigen::Matrix2d() << 1, 0, 0, 0).finished(), (Eigen::Matrix2d() << 0, 1, 1, 0).finished(),
                                (Eigen::Matrix2d() << 0, 0, 0, 1).finished()};
  for (int k = 0; k < 3; ++k) out[static_cast<std::size_t>(k)] = (R * E[k] * R.transpose() * f)(o.axis);
  return out;
}

}  // namespace

int Floor::within(double bound_m) const {
  return static_cast<int>(std::count_if(cells.begin(), cells.end(), [&](const FloorCell& c) { return std::abs(c.error_m) <= bound_m; }));
}
double Floor::rms_m() const {
  double ss = 0;
  for (const auto& c : cells) ss += c.error_m * c.error_m;
  return cells.empty() ? 0.0 : std::sqrt(ss / static_cast<double>(cells.size()));
}
double Floor::max_m() const {
  double m = 0;
  for (const auto& c : cells) m = std::max(m, std::abs(c.error_m));
  return m;
}

Floor per_series_floor(const measurement::DisplacementTable& table) {
  const auto obs = observations(table);
  std::map<int, std::vector<const Obs*>> by_series;
  for (const auto& o : obs) by_series[o.series].push_back(&o);
  Floor f;
  for (const auto& [s, rows] : by_series) {
    Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), 2);
    Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) {
      A.row(static_cast<Eigen::Index>(k)) << rows[k]->force_N, 1.0;
      b(static_cast<Eigen::Index>(k)) = rows[k]->value;
    }
    solve_into(A, b, rows, f);
  }
  return f;
}

Floor symmetric_floor(const measurement::DisplacementTable& table) {
  const auto obs = observations(table);
  std::map<std::string, std::vector<const Obs*>> by_point;
  for (const auto& o : obs) by_point[o.point].push_back(&o);
  Floor f;
  for (const auto& [point, rows] : by_point) {
    std::map<int, int> local;
    for (const Obs* o : rows) local.emplace(o->series, static_cast<int>(local.size()));
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), 3 + static_cast<Eigen::Index>(local.size()));
    Eigen::VectorXd b(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const auto cols = symmetric_columns(*rows[k], 0.0);
      const auto row = static_cast<Eigen::Index>(k);
      for (int j = 0; j < 3; ++j) A(row, j) = cols[static_cast<std::size_t>(j)];
      A(row, 3 + local[rows[k]->series]) = 1.0;
      b(row) = rows[k]->value;
    }
    solve_into(A, b, rows, f);
  }
  return f;
}

Floor rotation_invariant_floor(const measurement::DisplacementTable& table) {
  const auto obs = observations(table);
  // Group by radius (mirror points share it): the radius rounded to 0.1 mm.
  std::map<long, int> group;
  std::map<int, int> series;
  for (const auto& o : obs) {
    group.emplace(std::lround(std::hypot(o.x_m, o.y_m) * 1e4), static_cast<int>(group.size()));
    series.emplace(o.series, static_cast<int>(series.size()));
  }
  const auto n = static_cast<Eigen::Index>(obs.size());
  const Eigen::Index cols = 3 + 3 * static_cast<Eigen::Index>(group.size()) + static_cast<Eigen::Index>(series.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, cols);
  Eigen::VectorXd b(n);
  std::vector<const Obs*> rows;
  for (Eigen::Index k = 0; k < n; ++k) {
    const Obs& o = obs[static_cast<std::size_t>(k)];
    const auto base = symmetric_columns(o, 0.0);
    const auto local = symmetric_columns(o, std::atan2(o.y_m, o.x_m));
    const Eigen::Index g = 3 + 3 * group.at(std::lround(std::hypot(o.x_m, o.y_m) * 1e4));
    for (int j = 0; j < 3; ++j) {
      A(k, j) = base[static_cast<std::size_t>(j)];
      A(k, g + j) = local[static_cast<std::size_t>(j)];
    }
    A(k, cols - static_cast<Eigen::Index>(series.size()) + series.at(o.series)) = 1.0;
    b(k) = o.value;
    rows.push_back(&o);
  }
  Floor f;
  solve_into(A, b, rows, f);
  return f;
}

Floor model_misfit(const compliance::Model& model, const measurement::DisplacementTable& table) {
  const std::vector<Obs> obs = observations(table);
  int series = 0;
  for (const Obs& o : obs) series = std::max(series, o.series + 1);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(obs.size()), series);
  Eigen::VectorXd b(static_cast<Eigen::Index>(obs.size()));
  std::vector<const Obs*> rows;
  for (std::size_t k = 0; k < obs.size(); ++k) {
    const Obs& o = obs[k];
    const auto i = static_cast<Eigen::Index>(k);
    A(i, o.series) = 1.0;
    b(i) = o.value - (model.compliance({o.x_m, o.y_m}) * Eigen::Vector2d(o.fx, o.fy))(o.axis);
    rows.push_back(&o);
  }
  Floor f;
  solve_into(A, b, rows, f);
  return f;
}

}  // namespace stiffpath::simulation::testing
