// Reading, validating and writing the tidy displacement table (data/thesis/displacements.csv format).
#include "stiffpath/measurement/displacement_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/sha256.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/csv_columns.hpp"

namespace stiffpath::measurement {

const char* to_string(ForceDirection direction) noexcept {
  switch (direction) {
    case ForceDirection::plus_x: return "+x";
    case ForceDirection::minus_x: return "-x";
    case ForceDirection::plus_y: return "+y";
    case ForceDirection::minus_y: return "-y";
  }
  return "?";
}

double direction_x(ForceDirection d) noexcept {
  return d == ForceDirection::plus_x ? 1.0 : d == ForceDirection::minus_x ? -1.0 : 0.0;
}
double direction_y(ForceDirection d) noexcept {
  return d == ForceDirection::plus_y ? 1.0 : d == ForceDirection::minus_y ? -1.0 : 0.0;
}

DisplacementTable DisplacementTable::filter(const std::string& mechanism) const {
  if (mechanism.empty()) {
    const auto names = mechanisms();
    if (names.size() > 1) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + (n.empty() ? std::string("(none)") : n);
      throw Error(SourceLocation{source}, fmt::format("the table holds the rows of {} mechanisms ({}): name the one meant "
                                                      "(compliance.rows in the robot file, or --rows); pooling them "
                                                      "would mix two machines",
                                                      names.size(), list));
    }
    return *this;
  }
  DisplacementTable out{source, {}, sha256};
  for (const auto& row : rows) {
    if (row.mechanism == mechanism) out.rows.push_back(row);
  }
  return out;
}

std::vector<std::string> DisplacementTable::mechanisms() const {
  std::vector<std::string> out;
  for (const auto& row : rows) {
    if (std::find(out.begin(), out.end(), row.mechanism) == out.end()) out.push_back(row.mechanism);
  }
  return out;
}

namespace {
// Bounds of a displacement table's cells (docs/reliability.md): a planar robot's workspace within 10 m,
// load forces up to 100 kN, elastic displacements up to 100 mm and rotations up to 90 degrees.
constexpr double max_coordinate_mm = 1e4;
constexpr double max_force_N = 1e5;
constexpr double max_displacement_mm = 100.0;
constexpr double max_angle_deg = 90.0;

ForceDirection parse_direction(const core::CsvReader& csv, std::size_t col) {
  const std::string_view text = csv.text(col);
  if (text == "+x" || text == "x") return ForceDirection::plus_x;
  if (text == "-x") return ForceDirection::minus_x;
  if (text == "+y" || text == "y") return ForceDirection::plus_y;
  if (text == "-y") return ForceDirection::minus_y;
  csv.fail(col, fmt::format("'{}' is not a force direction (+x, -x, +y, -y)", text));
}

// A cell within ±limit (in the file's units), refused with its location and value otherwise.
double bounded(const core::CsvReader& csv, std::size_t col, double limit, const char* unit) {
  const double value = csv.number(col);
  if (std::abs(value) > limit) csv.fail(col, fmt::format("RANGE: {:g} is beyond ±{:g} {}", value, limit, unit));
  return value;
}

std::optional<double> scaled(const core::CsvReader& csv, std::size_t col, double factor, double limit, const char* unit) {
  if (csv.text(col).empty()) return std::nullopt;
  return bounded(csv, col, limit, unit) * factor;
}

ReadingSpread read_spread(const core::CsvReader& csv, std::size_t c_readings) {
  ReadingSpread s;
  const long n = csv.integer(c_readings);
  if (n < 2) csv.fail(c_readings, fmt::format("a spread needs 2 or more readings, got {}", n));
  s.readings = static_cast<int>(n);
  const double mm = 1e-3, deg = units::deg_to_rad(1.0);
  const std::pair<const char*, double*> fields[] = {{"dx_sd_mm", &s.dx_m}, {"dy_sd_mm", &s.dy_m},
                                                    {"dz_sd_mm", &s.dz_m}, {"rx_sd_deg", &s.rx_rad},
                                                    {"ry_sd_deg", &s.ry_rad}};
  for (const auto& [name, target] : fields) {
    const auto col = csv.column(name);
    const double v = csv.number(col);
    if (v < 0.0) csv.fail(col, fmt::format("a standard deviation cannot be negative, got {}", v));
    *target = v * (name[0] == 'r' ? deg : mm);
  }
  return s;
}

DisplacementTable read_table(core::CsvReader& csv, const std::string& source) {
  const int header_line = csv.line();
  const auto required = [&](std::string_view name) {
    return require_column(csv, name, header_line, kRequiredDisplacementColumns);
  };
  require_unit(csv, header_line, "x", "mm");  // before the required columns: x_m is named as a unit error
  require_unit(csv, header_line, "y", "mm");
  const auto c_dir = required("direction"), c_point = required("point");
  const auto c_x = required("x_mm"), c_y = required("y_mm"), c_fn = required("F_N");
  const auto c_dx = required("dx_mm"), c_dy = required("dy_mm");
  const auto c_mech = csv.find_column("mechanism"), c_step = csv.find_column("step");
  const auto c_kgf = csv.find_column("force_kgf"), c_nom = csv.find_column("F_nominal_N");
  const auto c_dz = csv.find_column("dz_mm"), c_rx = csv.find_column("rx_deg"), c_ry = csv.find_column("ry_deg");

  const auto c_readings = csv.find_column("readings");
  DisplacementTable table{source, {}, {}};
  std::set<std::tuple<std::string, int, std::string, int>> seen;
  std::map<std::tuple<std::string, int, std::string>, int> series_steps;  // steps numbered when there is no column
  while (csv.next()) {
    if (table.rows.size() >= core::max_table_rows) {
      throw Error(csv.where(), fmt::format("LIMIT: more than {} rows, the most a displacement table may hold",
                                           core::max_table_rows));
    }
    DisplacementRow row;
    row.line = csv.line();
    if (c_mech) row.mechanism = std::string(csv.name(*c_mech));
    row.direction = parse_direction(csv, c_dir);
    row.point = std::string(csv.name(c_point));
    if (row.point.empty()) csv.fail(c_point, "value is missing (empty cell)");
    row.x_m = units::mm_to_m(bounded(csv, c_x, max_coordinate_mm, "mm"));
    row.y_m = units::mm_to_m(bounded(csv, c_y, max_coordinate_mm, "mm"));
    if (c_step) {
      const long step = csv.integer(*c_step);
      if (step < 1) csv.fail(*c_step, fmt::format("load step must be 1 or more (step 0 is the reference), got {}", step));
      row.step = static_cast<int>(step);
    } else {
      row.step = ++series_steps[{row.mechanism, static_cast<int>(row.direction), row.point}];
    }
    row.force_N = bounded(csv, c_fn, max_force_N, "N");
    if (!(row.force_N > 0.0)) csv.fail(c_fn, fmt::format("force must be positive, got {}", row.force_N));
    row.force_kgf = c_kgf ? bounded(csv, *c_kgf, max_force_N / units::standard_gravity_m_s2, "kgf")
                          : row.force_N / units::standard_gravity_m_s2;
    row.nominal_force_N = c_nom ? bounded(csv, *c_nom, max_force_N, "N") : row.force_N;
    row.dx_m = scaled(csv, c_dx, 1e-3, max_displacement_mm, "mm");
    row.dy_m = scaled(csv, c_dy, 1e-3, max_displacement_mm, "mm");
    if (c_dz) row.dz_m = scaled(csv, *c_dz, 1e-3, max_displacement_mm, "mm");
    if (c_rx) row.rx_rad = scaled(csv, *c_rx, units::deg_to_rad(1.0), max_angle_deg, "deg");
    if (c_ry) row.ry_rad = scaled(csv, *c_ry, units::deg_to_rad(1.0), max_angle_deg, "deg");
    if (c_readings && !csv.text(*c_readings).empty()) row.spread = read_spread(csv, *c_readings);
    const auto key = std::make_tuple(row.mechanism, static_cast<int>(row.direction), row.point, row.step);
    if (!seen.insert(key).second) {
      throw Error(csv.where(),
                  fmt::format("duplicated row: {}direction {}, point {}, step {} appears twice",
                              row.mechanism.empty() ? "" : "mechanism " + row.mechanism + ", ",
                              to_string(row.direction), row.point, row.step));
    }
    table.rows.push_back(std::move(row));
  }
  if (table.rows.empty()) throw Error(SourceLocation{source}, "no data rows");
  return table;
}

// Refuses a row that the reader above would refuse, before anything is written: a table is never
// written that its own reader cannot read back (the row's line is that of the readings it came from).
void check_writable(const DisplacementTable& table, const DisplacementRow& r) {
  const SourceLocation where{table.source, r.line};
  const std::string what = fmt::format("point {} {} step {}", r.point, to_string(r.direction), r.step);
  const auto within = [&](const char* name, double value, double limit, const char* unit) {
    if (!(std::abs(value) <= limit)) {
      throw Error(where, fmt::format("RANGE: {} of {} is {:g} {}, beyond the ±{:g} {} a displacement table holds; "
                                     "no table written",
                                     name, what, value, unit, limit, unit));
    }
  };
  const auto text = [&](const char* name, const std::string& value) {
    if (value.find_first_of(",\"\r\n") != std::string::npos) {
      throw Error(where, fmt::format("{} '{}' holds a comma, quote or line break, which a table cell cannot; no table "
                                     "written",
                                     name, value));
    }
  };
  if (r.point.empty()) throw Error(where, "a row without a point name; no table written");
  text("point", r.point);
  text("mechanism", r.mechanism);
  within("x", units::m_to_mm(r.x_m), max_coordinate_mm, "mm");
  within("y", units::m_to_mm(r.y_m), max_coordinate_mm, "mm");
  within("F", r.force_N, max_force_N, "N");
  if (!(r.force_N > 0.0)) {
    throw Error(where, fmt::format("the load of {} is {:g} N, not positive; no table written", what, r.force_N));
  }
  within("force", r.force_kgf, max_force_N / units::standard_gravity_m_s2, "kgf");
  within("nominal force", r.nominal_force_N, max_force_N, "N");
  const std::pair<const char*, const std::optional<double>*> lengths[] = {{"dx", &r.dx_m}, {"dy", &r.dy_m}, {"dz", &r.dz_m}};
  for (const auto& [name, v] : lengths) {
    if (*v) within(name, units::m_to_mm(**v), max_displacement_mm, "mm");
  }
  const std::pair<const char*, const std::optional<double>*> angles[] = {{"rx", &r.rx_rad}, {"ry", &r.ry_rad}};
  for (const auto& [name, v] : angles) {
    if (*v) within(name, units::rad_to_deg(**v), max_angle_deg, "deg");
  }
  if (r.spread) {
    const auto& sd = *r.spread;
    for (const double v : {sd.dx_m * 1e3, sd.dy_m * 1e3, sd.dz_m * 1e3, units::rad_to_deg(sd.rx_rad), units::rad_to_deg(sd.ry_rad)}) {
      if (!(v >= 0.0 && v <= core::max_csv_magnitude)) {
        throw Error(where, fmt::format("a reading spread of {} is {:g}, not a finite standard deviation; no table written", what, v));
      }
    }
  }
}

std::string cell(const std::optional<double>& v, double factor, int decimals) {
  return v ? fmt::format("{:.{}f}", *v * factor, decimals) : std::string();
}
}  // namespace

core::DataRef thesis_dataset() { return {"thesis/displacements.csv", true}; }

DisplacementTable parse_displacement_table(const std::string& text, const std::string& label) {
  std::istringstream in(text);
  core::CsvReader csv(in, label);
  DisplacementTable table = read_table(csv, label);
  table.sha256 = core::sha256_hex(text);
  return table;
}

DisplacementTable load_displacement_table(const core::DataRef& file) {
  return parse_displacement_table(core::read_data(file, core::max_table_bytes), file.label());
}

DisplacementTable load_displacement_table(const std::string& path) {
  return load_displacement_table(core::parse_data_ref(path));
}

void save_displacement_table(const DisplacementTable& table, const std::string& path) {
  for (const auto& row : table.rows) check_writable(table, row);
  core::AtomicFile file(path);
  auto& out = file.stream();
  const bool with_spread =
      std::any_of(table.rows.begin(), table.rows.end(), [](const DisplacementRow& r) { return r.spread.has_value(); });
  out << kDisplacementColumns << (with_spread ? std::string(",") + kSpreadColumns : std::string()) << '\n';
  for (const auto& r : table.rows) {
    out << fmt::format("{},{},{},{:.3f},{:.3f},{},{:.4f},{:.4f},{:.4f},{},{},{},{},{}", r.mechanism,
                       to_string(r.direction), r.point, units::m_to_mm(r.x_m), units::m_to_mm(r.y_m), r.step,
                       r.force_kgf, r.force_N, r.nominal_force_N, cell(r.dx_m, 1e3, 6), cell(r.dy_m, 1e3, 6),
                       cell(r.dz_m, 1e3, 6), cell(r.rx_rad, units::rad_to_deg(1.0), 6),
                       cell(r.ry_rad, units::rad_to_deg(1.0), 6));
    if (with_spread && r.spread) {
      const auto& s = *r.spread;
      out << fmt::format(",{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}", s.readings, units::m_to_mm(s.dx_m),
                         units::m_to_mm(s.dy_m), units::m_to_mm(s.dz_m), units::rad_to_deg(s.rx_rad),
                         units::rad_to_deg(s.ry_rad));
    } else if (with_spread) {
      out << ",,,,,,";
    }
    out << '\n';
  }
  file.commit();
}

}  // namespace stiffpath::measurement
