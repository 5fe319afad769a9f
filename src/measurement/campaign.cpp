// Reading, validating and writing raw CMM campaign files (U and L per point, direction, load step, reading).
#include "stiffpath/measurement/campaign.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/campaign_checks.hpp"
#include "stiffpath/measurement/csv_columns.hpp"

namespace stiffpath::measurement {

namespace {

// Rejects columns that carry a quantity we read in a unit we do not read (Ux_in, force_lbf, x_m).
void check_units(const core::CsvReader& csv, int header_line) {
  for (const char* q : {"Ux", "Uy", "Uz", "Lx", "Ly", "Lz", "x", "y"}) require_unit(csv, header_line, q, "mm");
  for (std::size_t i = 0; i < csv.header().size(); ++i) {
    const std::string& name = csv.header()[i];
    if (name.starts_with("force_") && name != "force_kgf" && name != "force_N" && name != "force_nominal_N") {
      throw Error(SourceLocation{csv.label(), header_line, header_column(csv, i)},
                  fmt::format("column '{}': unit '{}' is not supported, use force_kgf or force_N", name,
                              name.substr(6)));
    }
  }
}

std::size_t require(const core::CsvReader& csv, const char* name, int header_line) {
  return require_column(csv, name, header_line, kCampaignColumns);
}

ForceDirection direction_cell(const core::CsvReader& csv, std::size_t col) {
  const std::string_view t = csv.text(col);
  if (t == "+x" || t == "x") return ForceDirection::plus_x;
  if (t == "-x") return ForceDirection::minus_x;
  if (t == "+y" || t == "y") return ForceDirection::plus_y;
  if (t == "-y") return ForceDirection::minus_y;
  csv.fail(col, fmt::format("'{}' is not a force direction (+x, -x, +y, -y)", t));
}

int non_negative_int(const core::CsvReader& csv, std::size_t col, long minimum) {
  const long v = csv.integer(col);
  if (v < minimum || v > 1000000) csv.fail(col, fmt::format("{} is out of range (must be {} or more)", v, minimum));
  return static_cast<int>(v);
}

}  // namespace

Campaign load_campaign(const std::string& path) {
  core::CsvReader csv(path);
  const int header_line = csv.line();
  check_units(csv, header_line);
  const auto c_point = require(csv, "point", header_line), c_x = require(csv, "x_mm", header_line);
  const auto c_y = require(csv, "y_mm", header_line), c_dir = require(csv, "direction", header_line);
  const auto c_step = require(csv, "step", header_line);
  const auto c_reading = csv.find_column("reading");
  const auto c_kgf = csv.find_column("force_kgf"), c_n = csv.find_column("force_N");
  if (c_kgf.has_value() == c_n.has_value()) {
    throw Error(SourceLocation{path, header_line, 1},
                c_kgf ? "both force_kgf and force_N columns are present; give the force once"
                      : "missing force column: give force_kgf (table 2.1's unit) or force_N");
  }
  const std::size_t c_force = c_kgf ? *c_kgf : *c_n;
  const auto c_nominal = csv.find_column("force_nominal_N");
  const double to_N = c_kgf ? units::standard_gravity_m_s2 : 1.0;
  std::size_t c_coord[6];
  const char* coord_names[6] = {"Ux_mm", "Uy_mm", "Uz_mm", "Lx_mm", "Ly_mm", "Lz_mm"};
  for (int k = 0; k < 6; ++k) c_coord[k] = require(csv, coord_names[k], header_line);

  Campaign campaign{path, c_kgf ? ForceUnit::kgf : ForceUnit::N, c_nominal.has_value(), {}};
  std::map<std::tuple<std::string, int, int, int>, int> seen;  // key → line
  while (csv.next()) {
    if (campaign.readings.size() >= core::max_table_rows) {
      throw Error(csv.where(), fmt::format("LIMIT: more than {} readings, the most a campaign may hold",
                                           core::max_table_rows));
    }
    CampaignReading r;
    r.line = csv.line();
    r.point = std::string(csv.name(c_point));
    if (r.point.empty()) csv.fail(c_point, "value is missing (empty cell)");
    r.x_m = units::mm_to_m(csv.number(c_x));
    r.y_m = units::mm_to_m(csv.number(c_y));
    r.direction = direction_cell(csv, c_dir);
    r.step = non_negative_int(csv, c_step, 0);
    r.reading = c_reading ? non_negative_int(csv, *c_reading, 1) : 1;
    const double force = csv.number(c_force);
    if (force < 0.0) csv.fail(c_force, fmt::format("force must not be negative, got {}", force));
    r.force_N = force * to_N;
    if (c_nominal) {
      const double nominal = csv.number(*c_nominal);
      if (!(nominal >= 0.0 && nominal <= 1e5)) csv.fail(*c_nominal, fmt::format("must lie in 0 … 100000 N, got {}", nominal));
      if (r.step == 0 && nominal != 0.0) csv.fail(*c_nominal, fmt::format("step 0 is the reference: its nominal load is 0, got {}", nominal));
      r.nominal_force_N = nominal;
    }
    for (int k = 0; k < 3; ++k) r.U[k] = units::mm_to_m(csv.number(c_coord[k]));
    for (int k = 0; k < 3; ++k) r.L[k] = units::mm_to_m(csv.number(c_coord[k + 3]));
    if ((r.U - r.L).norm() < 1e-6) csv.fail(c_coord[3], "U and L coincide: the replica axis is undefined");
    const auto key = std::make_tuple(r.point, static_cast<int>(r.direction), r.step, r.reading);
    if (const auto [it, inserted] = seen.emplace(key, r.line); !inserted) {
      csv.fail(c_reading ? *c_reading : c_step,
               fmt::format("duplicated reading: point {}, direction {}, step {}, reading {} already on line {}{}",
                           r.point, to_string(r.direction), r.step, r.reading, it->second,
                           c_reading ? "" : " (add a 'reading' column for repeated readings)"));
    }
    campaign.readings.push_back(std::move(r));
  }
  validate_campaign(campaign);
  return campaign;
}

void save_campaign(const Campaign& campaign, const std::string& path) {
  core::AtomicFile file(path);
  auto& out = file.stream();
  out << (campaign.has_nominal_forces
              ? "point,x_mm,y_mm,direction,step,reading,force_kgf,force_nominal_N,Ux_mm,Uy_mm,Uz_mm,Lx_mm,Ly_mm,Lz_mm"
              : kCampaignColumns)
      << '\n';
  for (const auto& r : campaign.readings) {
    const std::string nominal =
        campaign.has_nominal_forces ? fmt::format("{:.6f},", r.nominal_force_N.value_or(0.0)) : std::string();
    out << fmt::format("{},{:.3f},{:.3f},{},{},{},{:.6f},{}{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n", r.point,
                       units::m_to_mm(r.x_m), units::m_to_mm(r.y_m), to_string(r.direction), r.step, r.reading,
                       r.force_N / units::standard_gravity_m_s2, nominal, units::m_to_mm(r.U.x()),
                       units::m_to_mm(r.U.y()), units::m_to_mm(r.U.z()), units::m_to_mm(r.L.x()),
                       units::m_to_mm(r.L.y()), units::m_to_mm(r.L.z()));
  }
  file.commit();
}

}  // namespace stiffpath::measurement
