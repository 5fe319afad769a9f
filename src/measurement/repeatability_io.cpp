// Reading positioning-trial files (thesis table 3.2 format, optionally bidirectional) with located errors.
#include <fmt/format.h>

#include <set>
#include <sstream>
#include <tuple>

#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/csv_columns.hpp"
#include "stiffpath/measurement/repeatability.hpp"

namespace stiffpath::measurement {

namespace {

constexpr const char* kTrialColumns = "[mechanism,]point,x_mm,y_mm,trial,[approach,]err_x_mm,err_y_mm[,err_z_mm]";

std::optional<double> mm(const core::CsvReader& csv, std::optional<std::size_t> col) {
  if (!col) return std::nullopt;
  const auto v = csv.optional_number(*col);
  return v ? std::optional<double>(units::mm_to_m(*v)) : std::nullopt;
}

std::vector<PositioningTrial> read(core::CsvReader& csv) {
  const int header_line = csv.line();
  for (const char* q : {"err_x", "err_y", "err_z", "x", "y"}) require_unit(csv, header_line, q, "mm");
  auto column = [&](const char* name) { return require_column(csv, name, header_line, kTrialColumns); };
  const auto c_mech = csv.find_column("mechanism"), c_appr = csv.find_column("approach");
  const auto c_point = column("point"), c_x = column("x_mm"), c_y = column("y_mm");
  const auto c_trial = column("trial"), c_ex = column("err_x_mm"), c_ey = column("err_y_mm");
  const auto c_ez = csv.find_column("err_z_mm");
  std::vector<PositioningTrial> out;
  std::set<std::tuple<std::string, std::string, int, int>> seen;
  while (csv.next()) {
    if (out.size() >= core::max_table_rows) {
      throw Error(csv.where(), fmt::format("LIMIT: more than {} trials, the most a trials file may hold",
                                           core::max_table_rows));
    }
    PositioningTrial t;
    t.line = csv.line();
    if (c_mech) t.mechanism = std::string(csv.name(*c_mech));
    t.point = std::string(csv.name(c_point));
    if (t.point.empty()) csv.fail(c_point, "value is missing (empty cell)");
    t.x_m = units::mm_to_m(csv.number(c_x));
    t.y_m = units::mm_to_m(csv.number(c_y));
    const long trial = csv.integer(c_trial);
    if (trial < 1) csv.fail(c_trial, fmt::format("trial numbers start at 1, got {}", trial));
    t.trial = static_cast<int>(trial);
    if (c_appr) {
      const auto a = csv.text(*c_appr);
      if (a == "+" || a == "+1") {
        t.approach = 1;
      } else if (a == "-" || a == "-1") {
        t.approach = -1;
      } else {
        csv.fail(*c_appr, fmt::format("'{}' is not an approach direction (+ or -)", a));
      }
    }
    t.err_x_m = mm(csv, c_ex);
    t.err_y_m = mm(csv, c_ey);
    t.err_z_m = mm(csv, c_ez);
    if (!seen.insert({t.mechanism, t.point, t.approach, t.trial}).second) {
      csv.fail(c_trial, fmt::format("duplicated trial {} of point {}{}", t.trial, t.point,
                                    t.mechanism.empty() ? "" : " (" + t.mechanism + ")"));
    }
    out.push_back(std::move(t));
  }
  if (out.empty()) throw Error(SourceLocation{csv.label()}, "no trials in the file");
  return out;
}

}  // namespace

core::DataRef thesis_repeatability() { return {"thesis/repeatability.csv", true}; }

std::vector<PositioningTrial> load_trials(const core::DataRef& file) {
  std::istringstream in{core::read_data(file, core::max_table_bytes)};
  core::CsvReader csv(in, file.label());
  return read(csv);
}

std::vector<PositioningTrial> load_trials(const std::string& path) { return load_trials(core::parse_data_ref(path)); }

}  // namespace stiffpath::measurement
