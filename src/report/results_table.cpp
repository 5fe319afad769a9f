// Results tables for figs. 4.9–4.11: from the experiment's runs or from a user's CSV, with their provenance.
#include "stiffpath/report/results_table.hpp"

#include <fmt/format.h>

#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::report {

std::string check_source(const std::string& text) {
  if (text == "simulated" || text == "measured") return text;
  throw Error(fmt::format("source '{}': must be 'simulated' or 'measured'", text));
}

ResultsTable results_from_runs(const std::vector<simulation::RunResult>& results) {
  ResultsTable table{{}, "simulated", "experiment"};
  for (const auto& r : results) {
    table.rows.push_back({r.spec.robot, r.spec.motion, r.spec.compensated(),
                          r.spec.compensated() ? std::string(core::enum_name(r.spec.variant)) : std::string(),
                          r.spec.acceleration_m_s2 / units::standard_gravity_m_s2,
                          r.metrics.length_m * 1e3, r.metrics.deviation_area_m2 * 1e6});
  }
  return table;
}

ResultsTable load_results_csv(const std::string& path, const std::string& source_flag) {
  core::CsvReader csv(path);
  const std::size_t robot = csv.column("robot"), motion = csv.column("motion"), compensated = csv.column("compensated"),
                    g = csv.column("acceleration_g"), length = csv.column("length_mm"),
                    area = csv.column("deviation_area_mm2");
  const auto source = csv.find_column("source");
  const auto variant = csv.find_column("variant");
  ResultsTable table{{}, source_flag.empty() ? std::string() : check_source(source_flag), path};
  while (csv.next()) {
    ResultRow row;
    row.robot = std::string(csv.text(robot));
    row.motion = std::string(csv.text(motion));
    if (row.robot.empty()) csv.fail(robot, "empty robot name");
    if (row.motion.empty()) csv.fail(motion, "empty motion name");
    const long on = csv.integer(compensated);
    if (on != 0 && on != 1) csv.fail(compensated, fmt::format("must be 0 or 1, got {}", on));
    row.compensated = on == 1;
    if (variant && row.compensated) row.variant = std::string(csv.text(*variant));
    row.acceleration_g = csv.number(g);
    if (row.acceleration_g <= 0.0) csv.fail(g, "must be positive");
    row.length_mm = csv.number(length);
    if (row.length_mm < 0.0) csv.fail(length, "a length cannot be negative");
    row.deviation_area_mm2 = csv.number(area);
    if (row.deviation_area_mm2 < 0.0) csv.fail(area, "an area cannot be negative");
    if (source) {
      const std::string value(csv.text(*source));
      if (value != "simulated" && value != "measured") csv.fail(*source, "must be 'simulated' or 'measured', got '" + value + "'");
      if (table.source.empty()) table.source = value;
      if (value != table.source) {
        csv.fail(*source, fmt::format("'{}' where {} says '{}': one table holds one kind of result", value,
                                      source_flag.empty() ? "an earlier row" : "--source", table.source));
      }
    }
    table.rows.push_back(row);
  }
  if (table.rows.empty()) throw Error(SourceLocation{path}, "no results in the table");
  if (table.source.empty()) {
    throw Error(SourceLocation{path}, "say whether these results are simulated or measured: add a 'source' column "
                                      "or pass --source simulated|measured");
  }
  return table;
}

}  // namespace stiffpath::report
