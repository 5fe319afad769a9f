// ISO 9283 pose accuracy/repeatability per point and VDI/DGQ 3441 positioning figures per axis.
#include "stiffpath/measurement/repeatability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace stiffpath::measurement {

namespace {

using Group = std::vector<const PositioningTrial*>;

bool complete(const PositioningTrial& t) { return t.err_x_m && t.err_y_m; }

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); }

double sample_sd(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / (static_cast<double>(v.size()) - 1.0));
}

PoseStatistics pose_statistics(const Group& all) {
  PoseStatistics p;
  p.mechanism = all.front()->mechanism;
  p.point = all.front()->point;
  p.x_m = all.front()->x_m;
  p.y_m = all.front()->y_m;
  std::vector<double> ex, ey, ez;
  for (const auto* t : all) {
    if (!complete(*t)) {
      ++p.missing;
      continue;
    }
    ex.push_back(*t->err_x_m);
    ey.push_back(*t->err_y_m);
    ez.push_back(t->err_z_m.value_or(0.0));
  }
  p.trials = static_cast<int>(ex.size());
  if (p.trials < 2) return p;
  p.mean_x_m = mean(ex);
  p.mean_y_m = mean(ey);
  p.mean_z_m = mean(ez);
  p.ap_m = std::sqrt(p.mean_x_m * p.mean_x_m + p.mean_y_m * p.mean_y_m + p.mean_z_m * p.mean_z_m);
  std::vector<double> l;
  for (std::size_t j = 0; j < ex.size(); ++j) {
    l.push_back(std::sqrt(std::pow(ex[j] - p.mean_x_m, 2) + std::pow(ey[j] - p.mean_y_m, 2) +
                          std::pow(ez[j] - p.mean_z_m, 2)));
  }
  p.l_mean_m = mean(l);
  p.s_l_m = sample_sd(l);
  p.rp_m = p.l_mean_m + 3.0 * p.s_l_m;
  const auto [xmin, xmax] = std::minmax_element(ex.begin(), ex.end());
  const auto [ymin, ymax] = std::minmax_element(ey.begin(), ey.end());
  p.max_diff_x_m = *xmax - *xmin;
  p.max_diff_y_m = *ymax - *ymin;
  return p;
}

// VDI/DGQ 3441 for one axis; nullopt unless every point has ≥ 2 complete trials from each side.
std::optional<Vdi3441Axis> vdi3441(const std::string& mechanism, const std::vector<Group>& points, char axis) {
  Vdi3441Axis a;
  a.mechanism = mechanism;
  a.axis = axis;
  for (const auto& g : points) {
    std::vector<double> up, down;
    for (const auto* t : g) {
      if (!complete(*t)) continue;
      const double e = axis == 'x' ? *t->err_x_m : *t->err_y_m;
      if (t->approach > 0) up.push_back(e);
      if (t->approach < 0) down.push_back(e);
    }
    if (up.size() < 2 || down.size() < 2) return std::nullopt;
    ReversalPoint r;
    r.point = g.front()->point;
    r.mean_up_m = mean(up);
    r.mean_down_m = mean(down);
    r.s_up_m = sample_sd(up);
    r.s_down_m = sample_sd(down);
    r.mean_m = 0.5 * (r.mean_up_m + r.mean_down_m);
    r.reversal_span_m = std::abs(r.mean_up_m - r.mean_down_m);
    r.scatter_m = 6.0 * 0.5 * (r.s_up_m + r.s_down_m);
    a.points.push_back(r);
  }
  if (a.points.empty()) return std::nullopt;
  double lo = INFINITY, hi = -INFINITY, mean_lo = INFINITY, mean_hi = -INFINITY;
  for (const auto& r : a.points) {
    mean_lo = std::min(mean_lo, r.mean_m);
    mean_hi = std::max(mean_hi, r.mean_m);
    lo = std::min(lo, r.mean_m - 0.5 * r.reversal_span_m - 0.5 * r.scatter_m);
    hi = std::max(hi, r.mean_m + 0.5 * r.reversal_span_m + 0.5 * r.scatter_m);
    a.reversal_span_max_m = std::max(a.reversal_span_max_m, r.reversal_span_m);
    a.scatter_max_m = std::max(a.scatter_max_m, r.scatter_m);
    a.reversal_span_mean_m += r.reversal_span_m / static_cast<double>(a.points.size());
    a.scatter_mean_m += r.scatter_m / static_cast<double>(a.points.size());
  }
  a.position_deviation_m = mean_hi - mean_lo;
  a.uncertainty_m = hi - lo;
  return a;
}

}  // namespace

RepeatabilityReport analyse_repeatability(const std::vector<PositioningTrial>& trials) {
  RepeatabilityReport report;
  std::map<std::pair<std::string, std::string>, std::size_t> index;
  std::vector<Group> groups;
  for (const auto& t : trials) {
    const auto [it, inserted] = index.emplace(std::make_pair(t.mechanism, t.point), groups.size());
    if (inserted) groups.emplace_back();
    groups[it->second].push_back(&t);
  }
  std::map<std::string, std::vector<Group>> by_mechanism;
  std::vector<std::string> mechanisms;
  for (const auto& g : groups) {
    PoseStatistics p = pose_statistics(g);
    const std::string label = (p.mechanism.empty() ? "" : p.mechanism + " ") + p.point;
    if (p.trials < 2) {
      report.missing.push_back(fmt::format("{}: {} complete trial(s) of {}, 2 needed", label, p.trials, g.size()));
      continue;
    }
    if (!by_mechanism.contains(p.mechanism)) mechanisms.push_back(p.mechanism);
    by_mechanism[p.mechanism].push_back(g);
    report.points.push_back(std::move(p));
  }
  for (const auto& m : mechanisms) {
    for (char axis : {'x', 'y'}) {
      if (auto a = vdi3441(m, by_mechanism[m], axis)) report.vdi3441.push_back(std::move(*a));
    }
  }
  return report;
}

}  // namespace stiffpath::measurement
