// Symmetry of a displacement table about the x axis (y → −y), the thesis's validation of its procedure (§2.5).
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "stiffpath/measurement/data_check.hpp"

namespace stiffpath::measurement {

namespace {

ForceDirection mirrored(ForceDirection d) noexcept {
  switch (d) {
    case ForceDirection::plus_y: return ForceDirection::minus_y;
    case ForceDirection::minus_y: return ForceDirection::plus_y;
    default: return d;
  }
}

ForceDirection opposite(ForceDirection d) noexcept {
  switch (d) {
    case ForceDirection::plus_x: return ForceDirection::minus_x;
    case ForceDirection::minus_x: return ForceDirection::plus_x;
    case ForceDirection::plus_y: return ForceDirection::minus_y;
    case ForceDirection::minus_y: return ForceDirection::plus_y;
  }
  return d;
}

// Sign of a quantity under the mirror y → −y (rotations are axial vectors).
double mirror_sign(Quantity q) noexcept { return q == Quantity::dy || q == Quantity::rx ? -1.0 : 1.0; }

using Key = std::tuple<std::string, int, std::string, int>;  // mechanism, direction, point, step

}  // namespace

std::vector<SymmetryResult> check_symmetry(const DisplacementTable& table, const DataCheckOptions& options,
                                           std::vector<std::string>& skipped) {
  std::map<Key, const DisplacementRow*> cells;
  for (const auto& r : table.rows) cells[Key{r.mechanism, static_cast<int>(r.direction), r.point, r.step}] = &r;
  // Mirror point of each (mechanism, point), found by coordinates (x, −y) within 1 µm: the first such row
  // in the table's order, or nullptr. Rows are binned by their coordinates in µm, so a point's partner
  // is among the rows of the 3 × 3 bins around its mirror image (n log n, not n²).
  constexpr double tolerance_m = 1e-6;
  using Bin = std::tuple<std::string, long long, long long>;
  const auto bin_of = [&](double v) { return std::llround(std::floor(v / tolerance_m)); };
  std::map<Bin, std::vector<std::size_t>> bins;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const auto& p = table.rows[i];
    bins[Bin{p.mechanism, bin_of(p.x_m), bin_of(p.y_m)}].push_back(i);
  }
  std::map<std::pair<std::string, std::string>, const DisplacementRow*> partner_of;
  for (const auto& r : table.rows) {
    const auto key = std::make_pair(r.mechanism, r.point);
    if (partner_of.contains(key)) continue;
    const DisplacementRow* found = nullptr;
    std::size_t first = table.rows.size();
    const long long bx = bin_of(r.x_m), by = bin_of(-r.y_m);
    for (long long ix = bx - 1; ix <= bx + 1; ++ix) {
      for (long long iy = by - 1; iy <= by + 1; ++iy) {
        const auto it = bins.find(Bin{r.mechanism, ix, iy});
        if (it == bins.end()) continue;
        for (const std::size_t i : it->second) {
          const auto& p = table.rows[i];
          if (i < first && std::abs(p.x_m - r.x_m) < tolerance_m && std::abs(p.y_m + r.y_m) < tolerance_m) {
            first = i;
            break;  // a bin's rows are in table order
          }
        }
      }
    }
    if (first < table.rows.size()) found = &table.rows[first];
    partner_of[key] = found;
    if (!found) {
      skipped.push_back(fmt::format("symmetry: {} {} has no mirror point at ({:.3f}, {:.3f}) mm", r.mechanism,
                                    r.point, r.x_m * 1e3, -r.y_m * 1e3));
    }
  }
  std::vector<SymmetryResult> out;
  for (const auto& r : table.rows) {
    const DisplacementRow* mirror = partner_of.at(std::make_pair(r.mechanism, r.point));
    if (r.y_m > 1e-9 || !mirror) continue;  // each pair once, from its y ≤ 0 member
    // Partner series: the mirrored direction if measured, else its opposite (cells negated).
    double sign = 1.0;
    ForceDirection pd = mirrored(r.direction);
    if (!cells.contains(Key{r.mechanism, static_cast<int>(pd), mirror->point, r.step})) {
      pd = opposite(pd);
      sign = -1.0;
    }
    const auto it = cells.find(Key{r.mechanism, static_cast<int>(pd), mirror->point, r.step});
    if (it == cells.end()) continue;
    const DisplacementRow& p = *it->second;
    const bool self = p.point == r.point;
    for (Quantity q : kQuantities) {
      if (is_angle(q) && !options.ul_m) continue;  // no replica: angles are not checked (data_check.hpp)
      const double m = sign * mirror_sign(q);
      if (self && m > 0.0) continue;  // compares a cell with itself
      const auto a = value_of(r, q), b = value_of(p, q);
      if (!a || !b) continue;
      SymmetryResult s;
      s.mechanism = r.mechanism;
      s.point = r.point;
      s.partner = p.point;
      s.direction = r.direction;
      s.step = r.step;
      s.quantity = q;
      s.value = *b;
      s.expected = m * *a;
      s.tolerance = 2.0 * (is_angle(q) ? options.angle_accuracy_rad() : options.accuracy_m);
      s.flagged = std::abs(s.value - s.expected) > s.tolerance;
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace stiffpath::measurement
