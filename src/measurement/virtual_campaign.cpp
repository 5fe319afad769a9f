// Virtual CMM campaigns (truth → noisy U, L readings) and the linear stand-in truth built from a measured table.
#include "stiffpath/measurement/virtual_campaign.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::measurement {

namespace {

using Field = std::optional<double> DisplacementRow::*;
constexpr std::array<Field, 5> kFields = {&DisplacementRow::dx_m, &DisplacementRow::dy_m, &DisplacementRow::dz_m,
                                          &DisplacementRow::rx_rad, &DisplacementRow::ry_rad};
constexpr std::array<const char*, 5> kFieldNames = {"dx_mm", "dy_mm", "dz_mm", "rx_deg", "ry_deg"};

std::array<bool, 5> present(const DisplacementTable& table) {
  std::array<bool, 5> in_table{};
  for (const auto& r : table.rows) {
    for (std::size_t f = 0; f < kFields.size(); ++f) in_table[f] = in_table[f] || (r.*kFields[f]).has_value();
  }
  return in_table;
}

void check_options(const VirtualCampaignOptions& o) {
  if (o.readings_per_step < 1 || o.readings_per_step > 1000) throw Error("readings per step must be 1 … 1000");
  if (!(o.noise_sigma_m >= 0.0) || !std::isfinite(o.noise_sigma_m)) throw Error("noise σ must be >= 0");
  if (!(o.geometry.ul_m > 0.0) || !(o.geometry.ug_m >= 0.0)) throw Error("replica needs |UL| > 0 and |UG| >= 0");
  if (!(o.step0_kgf >= 0.0) || !std::isfinite(o.step0_kgf)) throw Error("step-0 load must be >= 0 kgf");
}

}  // namespace

Campaign simulate_campaign(const DisplacementTable& truth, const VirtualCampaignOptions& options) {
  check_options(options);
  if (truth.mechanisms().size() > 1) {
    throw Error(SourceLocation{truth.source}, "the truth table holds several mechanisms; filter it to one");
  }
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  auto noisy = [&](const Vec3& p) {
    return options.noise_sigma_m > 0.0
               ? Vec3(p + options.noise_sigma_m * Vec3(noise(rng), noise(rng), noise(rng)))
               : p;
  };
  // The truth's round loads travel with the readings, so that the campaign names them as a real one would.
  Campaign campaign{"virtual campaign of " + truth.source, ForceUnit::kgf, true, {}};
  auto add_step = [&](const DisplacementRow& row, int step, double kgf, const Vec3& g, const Tilt& t) {
    const Vec3 a = axis_from_tilt(t);
    const Vec3 U = g + options.geometry.ug_m * a;
    const Vec3 L = U - options.geometry.ul_m * a;
    for (int k = 1; k <= options.readings_per_step; ++k) {
      CampaignReading r{.point = row.point, .x_m = row.x_m, .y_m = row.y_m, .direction = row.direction,
                        .step = step, .reading = k, .force_N = units::kgf_to_N(kgf),
                        .nominal_force_N = step == 0 ? 0.0 : row.nominal_force_N, .U = noisy(U), .L = noisy(L)};
      campaign.readings.push_back(std::move(r));
    }
  };
  std::map<std::pair<std::string, int>, bool> started;
  for (const auto& row : truth.rows) {
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      if (!(row.*kFields[f])) {
        throw Error(SourceLocation{truth.source, row.line, 0},
                    fmt::format("column '{}': the truth needs every cell (point {}, step {}); see linear_truth()",
                                kFieldNames[f], row.point, row.step));
      }
    }
    const Vec3 g0(row.x_m, row.y_m, options.g_height_m);
    if (!started[{row.point, static_cast<int>(row.direction)}]) {
      started[{row.point, static_cast<int>(row.direction)}] = true;
      add_step(row, 0, options.step0_kgf, g0, options.initial_tilt);
    }
    const Vec3 g = g0 + Vec3(*row.dx_m, *row.dy_m, *row.dz_m);
    const Tilt t{options.initial_tilt.rx_rad + *row.rx_rad, options.initial_tilt.ry_rad + *row.ry_rad};
    add_step(row, row.step, row.force_kgf, g, t);
  }
  return campaign;
}

double step0_load_kgf(const DisplacementTable& table) {
  if (table.rows.empty()) return 0.0;
  const auto& first = table.rows.front();
  return std::max(0.0, std::round((first.force_kgf - first.force_N / units::standard_gravity_m_s2) * 1e6) / 1e6);
}

DisplacementTable linear_truth(const DisplacementTable& table) {
  using Key = std::tuple<std::string, int, std::string>;
  std::map<Key, std::array<std::pair<double, double>, 5>> sums;  // Σ F·v, Σ F² per field
  for (const auto& r : table.rows) {
    auto& s = sums[Key{r.mechanism, static_cast<int>(r.direction), r.point}];
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      if (const auto& v = r.*kFields[f]) {
        s[f].first += r.force_N * *v;
        s[f].second += r.force_N * r.force_N;
      }
    }
  }
  // A quantity the table does not have at all (dz, rx, ry are optional columns) is taken as zero.
  const std::array<bool, 5> in_table = present(table);
  DisplacementTable out{table.source, table.rows, {}};
  for (auto& r : out.rows) {
    const auto& s = sums.at(Key{r.mechanism, static_cast<int>(r.direction), r.point});
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      if (!in_table[f]) {
        r.*kFields[f] = 0.0;
        continue;
      }
      if (s[f].second <= 0.0) {
        throw Error(SourceLocation{table.source, r.line, 0},
                    fmt::format("column '{}': no value at all for {} {} {}", kFieldNames[f], r.mechanism,
                                to_string(r.direction), r.point));
      }
      r.*kFields[f] = r.force_N * s[f].first / s[f].second;
    }
    r.spread.reset();
  }
  return out;
}

bool has_gaps(const DisplacementTable& table) {
  const auto in_table = present(table);
  for (const auto& r : table.rows) {
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      if (in_table[f] && !(r.*kFields[f])) return true;
    }
  }
  return false;
}

DisplacementTable zero_absent_quantities(const DisplacementTable& table) {
  const auto in_table = present(table);
  DisplacementTable out = table;
  for (auto& r : out.rows) {
    for (std::size_t f = 0; f < kFields.size(); ++f) {
      if (!in_table[f]) r.*kFields[f] = 0.0;
    }
  }
  return out;
}

}  // namespace stiffpath::measurement
