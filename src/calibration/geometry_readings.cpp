// Loading and writing the geometry calibration's readings (joint angles and instrument coordinates).
#include "stiffpath/calibration/geometry_readings.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <tuple>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::calibration {

namespace {
constexpr const char* kColumns = "theta1_deg,theta2_deg,x_mm,y_mm[,z_mm][,reading]";

std::size_t require(const core::CsvReader& csv, const char* name, int header_line) {
  if (const auto c = csv.find_column(name)) return *c;
  throw Error(SourceLocation{csv.label(), header_line, 1},
              fmt::format("missing column '{}' (a readings file has the columns {})", name, kColumns));
}

// Refuses a column that carries one of our quantities in another unit (x_m, theta1_rad).
void check_units(const core::CsvReader& csv, int header_line) {
  const std::pair<const char*, const char*> quantities[] = {
      {"theta1", "deg"}, {"theta2", "deg"}, {"x", "mm"}, {"y", "mm"}, {"z", "mm"}};
  int column = 1;
  for (const std::string& name : csv.header()) {
    for (const auto& [q, unit] : quantities) {
      const std::string prefix = std::string(q) + "_";
      if (name.starts_with(prefix) && name != prefix + unit) {
        throw Error(SourceLocation{csv.label(), header_line, column},
                    fmt::format("column '{}': unit '{}' is not supported, give {}{}", name, name.substr(prefix.size()),
                                prefix, unit));
      }
    }
    column += static_cast<int>(name.size()) + 1;
  }
}

double within(const core::CsvReader& csv, std::size_t col, double limit, const char* unit) {
  const double v = csv.number(col);
  if (!(std::abs(v) <= limit)) csv.fail(col, fmt::format("{} is beyond +-{:g} {}", v, limit, unit));
  return v;
}
}  // namespace

GeometryReadings load_geometry_readings(const std::string& path) {
  core::CsvReader csv(path);
  const int header_line = csv.line();
  check_units(csv, header_line);
  const auto c_t1 = require(csv, "theta1_deg", header_line), c_t2 = require(csv, "theta2_deg", header_line);
  const auto c_x = require(csv, "x_mm", header_line), c_y = require(csv, "y_mm", header_line);
  const auto c_z = csv.find_column("z_mm"), c_reading = csv.find_column("reading");
  GeometryReadings out{path, c_z.has_value(), {}};
  std::map<std::tuple<double, double, int>, int> seen;  // (θ1, θ2, reading) → line
  while (csv.next()) {
    if (static_cast<int>(out.rows.size()) == kMaxGeometryReadings) {
      throw Error(csv.where(), fmt::format("more than {} readings: a geometry calibration needs a few dozen poses",
                                           kMaxGeometryReadings));
    }
    GeometryReading r;
    r.line = csv.line();
    const double t1 = within(csv, c_t1, kMaxJointReading_deg, "deg"), t2 = within(csv, c_t2, kMaxJointReading_deg, "deg");
    r.q_rad = {units::deg_to_rad(t1), units::deg_to_rad(t2)};
    r.point_m.x() = units::mm_to_m(within(csv, c_x, kMaxInstrumentCoordinate_mm, "mm"));
    r.point_m.y() = units::mm_to_m(within(csv, c_y, kMaxInstrumentCoordinate_mm, "mm"));
    if (c_z) r.point_m.z() = units::mm_to_m(within(csv, *c_z, kMaxInstrumentCoordinate_mm, "mm"));
    if (c_reading) {
      const long n = csv.integer(*c_reading);
      if (n < 1 || n > kMaxGeometryReadings) {
        csv.fail(*c_reading, fmt::format("{} is out of range (readings are numbered 1, 2, ...)", n));
      }
      r.reading = static_cast<int>(n);
    }
    const auto [it, fresh] = seen.try_emplace({t1, t2, r.reading}, r.line);
    if (!fresh) {
      throw Error(csv.where(c_reading ? *c_reading : c_t1),
                  fmt::format("pose (theta1 = {} deg, theta2 = {} deg) reading {} was already given on line {}{}", t1,
                              t2, r.reading, it->second,
                              c_reading ? "" : " (number repeated readings in a 'reading' column)"));
    }
    out.rows.push_back(r);
  }
  if (out.rows.empty()) throw Error(SourceLocation{path, header_line, 1}, "the readings file has no readings");
  return out;
}

void save_geometry_readings(const GeometryReadings& readings, const std::string& path) {
  core::AtomicFile file(path);
  auto& out = file.stream();
  out << (readings.has_z ? "theta1_deg,theta2_deg,x_mm,y_mm,z_mm,reading\n" : "theta1_deg,theta2_deg,x_mm,y_mm,reading\n");
  for (const auto& r : readings.rows) {
    out << fmt::format("{:.9f},{:.9f},{:.6f},{:.6f}", units::rad_to_deg(r.q_rad.x()), units::rad_to_deg(r.q_rad.y()),
                       units::m_to_mm(r.point_m.x()), units::m_to_mm(r.point_m.y()));
    if (readings.has_z) out << fmt::format(",{:.6f}", units::m_to_mm(r.point_m.z()));
    out << fmt::format(",{}\n", r.reading);
  }
  file.commit();
}

}  // namespace stiffpath::calibration
