// Leave-one-out cross-validation: grid models by neighbour interpolation, physical models by refitting.
#include "stiffpath/compliance/cross_validation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

#include "stiffpath/compliance/fit_budget.hpp"
#include "stiffpath/compliance/grid.hpp"
#include "stiffpath/compliance/grid_model.hpp"
#include "stiffpath/compliance/physical_model.hpp"
#include "stiffpath/compliance/physical_spline_model.hpp"
#include "stiffpath/compliance/uncertainty.hpp"

namespace stiffpath::compliance {

namespace {
struct Prediction {
  Mat2 compliance;
  Vec2 offset;
  std::optional<PredictionUncertainty> uncertainty;  // learnt from the other points only
};
using Predictor = std::function<std::optional<Prediction>(std::size_t held_out)>;

// The highest-load sample of each load direction (x-loaded, y-loaded) of a point.
std::vector<const PointSample*> reference_samples(const PointSamples& point) {
  const PointSample* best[2] = {nullptr, nullptr};
  for (const auto& s : point.samples) {
    const int axis = s.force_N.y() == 0.0 ? 0 : s.force_N.x() == 0.0 ? 1 : -1;
    if (axis < 0) continue;
    if (!best[axis] || s.force_N.norm() > best[axis]->force_N.norm()) best[axis] = &s;
  }
  std::vector<const PointSample*> out;
  for (auto* b : best) {
    if (b) out.push_back(b);
  }
  return out;
}

CvMethod evaluate(FitMethod name, const std::string& description, const std::vector<PointSamples>& points,
                  const std::vector<bool>& interior, ZeroForce zero_force, const Predictor& predict) {
  CvMethod m{name, description, {}, 0, 0.0, 0.0, 0.0, 0, 0, 0.0};
  double sum = 0.0, interior_sum = 0.0;
  int interior_count = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    CvPoint r;
    r.id = points[k].id;
    r.position = points[k].position;
    r.interior = interior[k];
    if (const auto pred = predict(k)) {
      double abs_sum = 0.0, vec_sum = 0.0;
      int components = 0, loads = 0;
      for (const PointSample* s : reference_samples(points[k])) {
        Vec2 d = pred->compliance * s->force_N;
        if (zero_force == ZeroForce::thesis_raw) d += pred->offset;
        Vec2 err = Vec2::Zero();
        if (s->dx_m) {
          err.x() = d.x() - *s->dx_m;
          abs_sum += std::abs(err.x());
          ++components;
        }
        if (s->dy_m) {
          err.y() = d.y() - *s->dy_m;
          abs_sum += std::abs(err.y());
          ++components;
        }
        vec_sum += err.norm();
        ++loads;
        Vec2 band = Vec2::Zero();
        if (pred->uncertainty) {
          const Mat2 cov = pred->uncertainty->measurement_covariance(points[k].position, s->force_N);
          band = pred->uncertainty->band_factor() * Vec2(std::sqrt(cov(0, 0)), std::sqrt(cov(1, 1)));
          const std::optional<double>* measured[2] = {&s->dx_m, &s->dy_m};
          for (int a = 0; a < 2; ++a) {
            if (!*measured[a]) continue;
            ++m.band_cells;
            m.inside_band += std::abs(err[a]) <= band[a] ? 1 : 0;
            m.mean_band_um += band[a] * 1e6;
          }
        }
        r.loads.push_back({s->force_N, s->dx_m, s->dy_m, d, band});
      }
      if (components > 0) {
        r.predicted = true;
        r.mean_abs_error_um = abs_sum / components * 1e6;
        r.mean_vector_error_um = vec_sum / loads * 1e6;
        sum += r.mean_abs_error_um;
        m.max_um = std::max(m.max_um, r.mean_abs_error_um);
        ++m.predicted;
        if (r.interior) {
          interior_sum += r.mean_abs_error_um;
          ++interior_count;
        }
      }
    }
    m.points.push_back(r);
  }
  m.mean_um = m.predicted > 0 ? sum / m.predicted : 0.0;
  if (m.band_cells > 0) m.mean_band_um /= m.band_cells;
  m.interior_mean_um = interior_count > 0 ? interior_sum / interior_count : 0.0;
  return m;
}

// Interpolates a held-out node linearly from its neighbours along x, else along y (nullopt at corners); `used`
// receives the two neighbours' node indices.
std::optional<Prediction> from_neighbours(const Grid& grid, const std::vector<Prediction>& by_node, int node,
                                          std::array<int, 2>* used = nullptr) {
  const int ny = static_cast<int>(grid.ys.size());
  const int i = node / ny, j = node % ny;
  const auto blend = [&](int a, int b, double t) {
    const Prediction& pa = by_node[static_cast<std::size_t>(a)];
    const Prediction& pb = by_node[static_cast<std::size_t>(b)];
    if (used) *used = {a, b};
    return Prediction{(1 - t) * pa.compliance + t * pb.compliance, (1 - t) * pa.offset + t * pb.offset, std::nullopt};
  };
  if (i > 0 && i + 1 < static_cast<int>(grid.xs.size())) {
    const auto ui = static_cast<std::size_t>(i);
    const double t = (grid.xs[ui] - grid.xs[ui - 1]) / (grid.xs[ui + 1] - grid.xs[ui - 1]);
    return blend(grid.node(i - 1, j), grid.node(i + 1, j), t);
  }
  if (j > 0 && j + 1 < ny) {
    const auto uj = static_cast<std::size_t>(j);
    const double t = (grid.ys[uj] - grid.ys[uj - 1]) / (grid.ys[uj + 1] - grid.ys[uj - 1]);
    return blend(grid.node(i, j - 1), grid.node(i, j + 1), t);
  }
  return std::nullopt;
}

// A physical method's model fitted to `points`.
std::unique_ptr<Model> fit_physical_method(FitMethod method, const std::vector<PointSamples>& points,
                                           const kinematics::FiveBarGeometry& geometry, const std::string& source) {
  switch (method) {
    case FitMethod::physical_spline: return fit_physical_spline_model(points, geometry, source, false);
    case FitMethod::physical_0: return fit_physical_model(points, geometry, 0, source, false);
    case FitMethod::physical: return fit_physical_model(points, geometry, 1, source, false);
    case FitMethod::physical_2: return fit_physical_model(points, geometry, 2, source, false);
    case FitMethod::bilinear:
    case FitMethod::symmetric: break;
  }
  throw Error(fmt::format("{} is not a model-based compliance method", core::enum_name(method)));
}
}  // namespace

CvReport cross_validate(const std::vector<PointSamples>& points, const kinematics::FiveBarGeometry& geometry,
                        const std::string& source, ZeroForce zero_force, bool with_uncertainty) {
  check_cv_budget(points, source);
  CvReport report;
  report.source = source;
  report.zero_force = zero_force;
  // Interior: strictly inside the bounding rectangle of all points (1 µm tolerance).
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& p : points) {
    x0 = std::min(x0, p.position.x());
    x1 = std::max(x1, p.position.x());
    y0 = std::min(y0, p.position.y());
    y1 = std::max(y1, p.position.y());
  }
  std::vector<bool> interior;
  for (const auto& p : points) {
    interior.push_back(p.position.x() > x0 + 1e-6 && p.position.x() < x1 - 1e-6 && p.position.y() > y0 + 1e-6 &&
                       p.position.y() < y1 - 1e-6);
  }

  std::vector<Vec2> positions;
  for (const auto& p : points) positions.push_back(p.position);
  std::vector<int> node_of;
  std::optional<Grid> grid;
  try {
    grid = Grid::from_positions(positions, node_of, source);
  } catch (const Error& e) {
    for (const FitMethod m : {FitMethod::bilinear, FitMethod::symmetric}) {
      report.skipped.push_back({m, std::string("needs a full rectangular grid: ") + e.message()});
    }
  }
  std::vector<Prediction> bilinear(points.size()), symmetric(points.size());
  if (grid) {
    try {
      for (std::size_t k = 0; k < points.size(); ++k) {
        const PointFit f = fit_point(points[k], source);
        bilinear[static_cast<std::size_t>(node_of[k])] = {f.compliance(), f.offset(), std::nullopt};
        const GridNode n = fit_symmetric_node(points[k], source);
        symmetric[static_cast<std::size_t>(node_of[k])] = {n.compliance, n.offset, std::nullopt};
      }
    } catch (const Error& e) {
      grid.reset();
      for (const FitMethod m : {FitMethod::bilinear, FitMethod::symmetric}) report.skipped.push_back({m, e.message()});
    }
  }
  if (grid) {
    // The band of a held-out node: the grid method's uncertainty learnt from the other nodes whose neighbour
    // predictions do not use it.
    const auto grid_method = [&](FitMethod name, const char* description, const std::vector<Prediction>& by_node) {
      std::vector<LooCompliance> loo;
      if (with_uncertainty) loo = leave_one_out_compliance(name, points, geometry, source);
      report.methods.push_back(evaluate(name, description, points, interior, zero_force, [&](std::size_t k) {
        auto p = from_neighbours(*grid, by_node, node_of[k]);
        if (p && with_uncertainty) {
          std::vector<PointSamples> rest;
          std::vector<LooResidual> residuals;
          for (std::size_t j = 0; j < points.size(); ++j) {
            if (j == k) continue;
            rest.push_back(points[j]);
            const auto& l = loo[j];
            if (!l.predicted || std::find(l.used.begin(), l.used.end(), k) != l.used.end()) continue;
            residuals.push_back({points[j].position, *l.predicted - fit_point(points[j], source).compliance()});
          }
          if (!residuals.empty() && rest.size() >= 4) {
            p->uncertainty = estimate_uncertainty(rest, residuals, UncertaintyBasis::interpolation,
                                                  name == FitMethod::symmetric, source);
          }
        }
        return p;
      }));
    };
    grid_method(FitMethod::bilinear, "thesis eqs. 4.8-4.12: per-point fits, bilinear between points", bilinear);
    grid_method(FitMethod::symmetric, "per-point fit with C = C^T > 0 (reciprocity), bilinear between", symmetric);
  }
  // The model-based methods: refitted on every point but k, asked at k (extrapolating beyond the rest).
  const auto refit_method = [&](FitMethod name, const std::string& description, auto fit) {
    try {
      report.methods.push_back(evaluate(name, description, points, interior, zero_force, [&](std::size_t k) {
        std::vector<PointSamples> rest;
        for (std::size_t m = 0; m < points.size(); ++m) {
          if (m != k) rest.push_back(points[m]);
        }
        const auto model = fit(rest);
        model->set_outside_policy(OutsidePolicy::extrapolate);
        Prediction p{model->compliance(points[k].position), Vec2::Zero(), std::nullopt};
        if (with_uncertainty) p.uncertainty = estimate_method_uncertainty(name, rest, geometry, source);
        return std::optional<Prediction>(p);
      }));
    } catch (const Error& e) {
      report.skipped.push_back({name, e.message()});
    }
  };
  for (int order = 0; order <= 2; ++order) {
    refit_method(order == 0 ? FitMethod::physical_0 : order == 1 ? FitMethod::physical : FitMethod::physical_2,
                 "five-bar statics C = U^-T D(p) U^-1, D polynomial of order " + std::to_string(order),
                 [&](const std::vector<PointSamples>& rest) { return fit_physical_model(rest, geometry, order, source, false); });
  }
  refit_method(FitMethod::physical_spline, "physical (order 1) + thin-plate smoothing spline of its residual at the points",
               [&](const std::vector<PointSamples>& rest) { return fit_physical_spline_model(rest, geometry, source, false); });
  return report;
}

std::vector<LooCompliance> leave_one_out_compliance(FitMethod method, const std::vector<PointSamples>& points,
                                                    const kinematics::FiveBarGeometry& geometry, const std::string& source) {
  std::vector<LooCompliance> out(points.size());
  if (method == FitMethod::bilinear || method == FitMethod::symmetric) {
    std::vector<Vec2> positions;
    for (const auto& p : points) positions.push_back(p.position);
    std::vector<int> node_of;
    const Grid grid = Grid::from_positions(positions, node_of, source);
    std::vector<Prediction> by_node(points.size());
    std::vector<std::size_t> point_of(points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      const auto node = static_cast<std::size_t>(node_of[k]);
      point_of[node] = k;
      if (method == FitMethod::bilinear) {
        const PointFit f = fit_point(points[k], source);
        by_node[node] = {f.compliance(), f.offset(), std::nullopt};
      } else {
        const GridNode n = fit_symmetric_node(points[k], source);
        by_node[node] = {n.compliance, n.offset, std::nullopt};
      }
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
      std::array<int, 2> used{};
      if (const auto p = from_neighbours(grid, by_node, node_of[k], &used)) {
        out[k].predicted = p->compliance;
        out[k].used = {point_of[static_cast<std::size_t>(used[0])], point_of[static_cast<std::size_t>(used[1])]};
      }
    }
    return out;
  }
  for (std::size_t k = 0; k < points.size(); ++k) {
    std::vector<PointSamples> rest;
    for (std::size_t m = 0; m < points.size(); ++m) {
      if (m != k) rest.push_back(points[m]);
    }
    auto model = fit_physical_method(method, rest, geometry, source);
    model->set_outside_policy(OutsidePolicy::extrapolate);
    out[k].predicted = model->compliance(points[k].position);
  }
  return out;
}

FitMethod favoured_method(const CvReport& report, std::vector<std::pair<FitMethod, double>>* scores) {
  if (report.methods.empty()) throw Error(SourceLocation{report.source}, "no compliance method can run on these points");
  // The points every method predicted.
  std::vector<bool> common(report.methods.front().points.size(), true);
  for (const auto& m : report.methods) {
    for (std::size_t k = 0; k < m.points.size() && k < common.size(); ++k) common[k] = common[k] && m.points[k].predicted;
  }
  std::optional<FitMethod> best;
  double best_score = 0.0;
  for (const auto& m : report.methods) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t k = 0; k < m.points.size() && k < common.size(); ++k) {
      if (common[k]) {
        sum += m.points[k].mean_abs_error_um;
        ++n;
      }
    }
    const double score = n > 0 ? sum / n : std::numeric_limits<double>::infinity();
    if (scores) scores->emplace_back(m.method, score);
    if (!best || score < best_score) {
      best = m.method;
      best_score = score;
    }
  }
  return *best;
}

}  // namespace stiffpath::compliance
