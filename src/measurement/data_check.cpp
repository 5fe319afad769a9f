// Linearity, reciprocity (Maxwell–Betti) and OC-vs-SC checks of a displacement table; symmetry is in symmetry_check.cpp.
#include "stiffpath/measurement/data_check.hpp"

#include <fmt/format.h>

#include <algorithm>

#include <cmath>
#include <map>
#include <tuple>

#include "stiffpath/core/error.hpp"

namespace stiffpath::measurement {

const char* to_string(Quantity q) noexcept {
  switch (q) {
    case Quantity::dx: return "dx";
    case Quantity::dy: return "dy";
    case Quantity::dz: return "dz";
    case Quantity::rx: return "rx";
    case Quantity::ry: return "ry";
  }
  return "?";
}

std::optional<double> value_of(const DisplacementRow& row, Quantity q) noexcept {
  switch (q) {
    case Quantity::dx: return row.dx_m;
    case Quantity::dy: return row.dy_m;
    case Quantity::dz: return row.dz_m;
    case Quantity::rx: return row.rx_rad;
    case Quantity::ry: return row.ry_rad;
  }
  return std::nullopt;
}

int DataCheckReport::flagged_count() const noexcept {
  int n = 0;
  for (const auto& r : linearity) n += r.flagged;
  for (const auto& r : symmetry) n += r.flagged;
  for (const auto& r : reciprocity) n += r.flagged;
  for (const auto& r : comparison) n += r.flagged;
  return n;
}

namespace {

using SeriesKey = std::tuple<std::string, std::string, int>;  // mechanism, point, direction
using Series = std::vector<const DisplacementRow*>;

double force_of(const DisplacementRow& r, const DataCheckOptions& o) {
  return o.nominal_forces ? r.nominal_force_N : r.force_N;
}

// Signed force components and the quantity's values over the rows of a series that have it.
void collect(const Series& s, Quantity q, const DataCheckOptions& o, std::vector<double>& f, std::vector<double>& v,
             double direction_sign) {
  for (const auto* r : s) {
    if (const auto value = value_of(*r, q)) {
      f.push_back(direction_sign * force_of(*r, o));
      v.push_back(*value);
    }
  }
}

void check_reciprocity(const std::map<SeriesKey, Series>& series, const DataCheckOptions& o, DataCheckReport& rep) {
  std::map<std::pair<std::string, std::string>, std::pair<const Series*, const Series*>> at_point;  // x, y series
  for (const auto& [key, s] : series) {
    const auto d = static_cast<ForceDirection>(std::get<2>(key));
    auto& slot = at_point[{std::get<0>(key), std::get<1>(key)}];
    (direction_x(d) != 0.0 ? slot.first : slot.second) = &s;
  }
  for (const auto& [key, pair] : at_point) {
    if (!pair.first || !pair.second) {
      rep.skipped.push_back(fmt::format("reciprocity: {} {} lacks a load along {}", key.first, key.second,
                                        pair.first ? "y" : "x"));
      continue;
    }
    std::vector<double> fx, dy, fy, dx;
    collect(*pair.first, Quantity::dy, o, fx, dy, direction_x(pair.first->front()->direction));
    collect(*pair.second, Quantity::dx, o, fy, dx, direction_y(pair.second->front()->direction));
    if (fx.empty() || fy.empty()) continue;
    ReciprocityResult r;
    r.mechanism = key.first;
    r.point = key.second;
    r.c_yx_m_per_N = slope_through_origin(fx, dy);
    r.c_xy_m_per_N = slope_through_origin(fy, dx);
    for (double f : fx) r.max_force_N = std::max(r.max_force_N, std::abs(f));
    for (double f : fy) r.max_force_N = std::max(r.max_force_N, std::abs(f));
    r.difference_m = std::abs(r.c_xy_m_per_N - r.c_yx_m_per_N) * r.max_force_N;
    r.tolerance = 2.0 * o.accuracy_m;
    r.flagged = r.difference_m > r.tolerance;
    rep.reciprocity.push_back(r);
  }
}

void compare_mechanisms(const DisplacementTable& table, const DataCheckOptions& o, DataCheckReport& rep) {
  std::map<std::tuple<std::string, int, int>, std::pair<const DisplacementRow*, const DisplacementRow*>> cells;
  for (const auto& r : table.rows) {
    if (r.mechanism != "OC" && r.mechanism != "SC") continue;
    auto& slot = cells[{r.point, static_cast<int>(r.direction), r.step}];
    (r.mechanism == "OC" ? slot.first : slot.second) = &r;
  }
  auto total = [](const DisplacementRow& r) { return std::sqrt(*r.dx_m * *r.dx_m + *r.dy_m * *r.dy_m + *r.dz_m * *r.dz_m); };
  for (const auto& [key, pair] : cells) {
    const auto* oc = pair.first;
    const auto* sc = pair.second;
    if (!oc || !sc) continue;
    if (!(oc->dx_m && oc->dy_m && oc->dz_m && sc->dx_m && sc->dy_m && sc->dz_m)) continue;
    MechanismComparison c;
    c.point = std::get<0>(key);
    c.direction = static_cast<ForceDirection>(std::get<1>(key));
    c.step = std::get<2>(key);
    c.force_N = force_of(*oc, o);
    c.oc_total_m = total(*oc);
    c.sc_total_m = total(*sc);
    c.tolerance = 2.0 * o.accuracy_m;
    c.flagged = c.oc_total_m > c.sc_total_m + c.tolerance;
    rep.comparison.push_back(c);
  }
}

}  // namespace

DataCheckReport check_displacements(const DisplacementTable& table, const DataCheckOptions& options) {
  if (!(options.accuracy_m > 0.0) || !std::isfinite(options.accuracy_m) || (options.ul_m && !(*options.ul_m > 0.0))) {
    throw Error("data check: the accuracy and |UL| must be positive");
  }
  DataCheckReport rep;
  rep.source = table.source;
  rep.options = options;
  std::map<SeriesKey, Series> series;
  std::vector<SeriesKey> order;
  for (const auto& r : table.rows) {
    const SeriesKey key{r.mechanism, r.point, static_cast<int>(r.direction)};
    auto& s = series[key];
    if (s.empty()) order.push_back(key);
    s.push_back(&r);
  }
  // Quantities the table does not have at all (dz, rx, ry are optional columns) are not checked.
  std::vector<Quantity> measured;
  for (Quantity q : kQuantities) {
    if (std::any_of(table.rows.begin(), table.rows.end(), [&](const DisplacementRow& r) { return value_of(r, q); })) {
      if (is_angle(q) && !options.ul_m) {
        rep.not_applicable.push_back(fmt::format("{}: the robot has no replica, whose |UL| sets an angle's accuracy",
                                                 to_string(q)));
        continue;
      }
      measured.push_back(q);
    }
  }
  for (const auto& key : order) {
    for (Quantity q : measured) {
      std::vector<double> f, v;
      collect(series[key], q, options, f, v, 1.0);
      LinearityResult l;
      l.mechanism = std::get<0>(key);
      l.point = std::get<1>(key);
      l.direction = static_cast<ForceDirection>(std::get<2>(key));
      l.quantity = q;
      l.fit = fit_line(f, v);
      l.tolerance = is_angle(q) ? options.angle_accuracy_rad() : options.accuracy_m;
      // A line through fewer than three cells fits them exactly (one cell: slope 0): nothing is checked.
      if (l.fit.n < 3) {
        rep.skipped.push_back(fmt::format("linearity: {} {} {} {}: only {} cell(s)", l.mechanism,
                                          to_string(l.direction), l.point, to_string(q), l.fit.n));
        continue;
      }
      l.flagged = l.fit.max_residual > l.tolerance;
      rep.linearity.push_back(l);
    }
  }
  if (options.mirror_symmetric) {
    rep.symmetry = check_symmetry(table, options, rep.skipped);
  } else {
    rep.not_applicable.push_back("symmetry: the robot is not its own mirror image about y = 0");
  }
  check_reciprocity(series, options, rep);
  if (table.mechanisms().size() < 2) {
    rep.not_applicable.push_back("OC vs SC: the table holds the rows of one mechanism");
  } else {
    compare_mechanisms(table, options, rep);
  }
  return rep;
}

}  // namespace stiffpath::measurement
