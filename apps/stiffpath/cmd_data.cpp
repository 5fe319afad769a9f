// `stiffpath data check FILE.csv`: linearity, symmetry, reciprocity and OC-vs-SC checks of a displacement table.
#include <fmt/format.h>

#include <algorithm>
#include <memory>

#include "bounded.hpp"
#include "commands.hpp"
#include "robot_flags.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/data_check.hpp"

namespace stiffpath::cli {

namespace {
using namespace measurement;

struct DataCheckCli {
  std::string file;
  std::string robot;
  bool robot_given = false;
  double accuracy_um = 23.0;
  bool nominal_forces = false;
  bool json = false;
};

// Quantities in mm or deg (per unit force: mm/N, deg/N) for display.
double display(Quantity q, double si) { return is_angle(q) ? units::rad_to_deg(si) : units::m_to_mm(si); }
const char* unit(Quantity q) { return is_angle(q) ? "deg" : "mm"; }

nlohmann::json to_json(const DataCheckReport& r) {
  nlohmann::json lin = nlohmann::json::array(), sym = nlohmann::json::array(), rec = nlohmann::json::array(),
                 cmp = nlohmann::json::array();
  for (const auto& l : r.linearity) {
    const std::string u = unit(l.quantity);
    lin.push_back({{"mechanism", l.mechanism}, {"direction", to_string(l.direction)}, {"point", l.point},
                   {"quantity", to_string(l.quantity)}, {"n", l.fit.n},
                   {"slope_" + u + "_per_N", tidy(display(l.quantity, l.fit.slope))},
                   {"intercept_" + u, tidy(display(l.quantity, l.fit.intercept))}, {"r2", tidy(l.fit.r_squared)},
                   {"max_residual_" + u, tidy(display(l.quantity, l.fit.max_residual))},
                   {"tolerance_" + u, tidy(display(l.quantity, l.tolerance))}, {"flagged", l.flagged}});
  }
  for (const auto& s : r.symmetry) {
    const std::string u = unit(s.quantity);
    sym.push_back({{"mechanism", s.mechanism}, {"direction", to_string(s.direction)}, {"point", s.point},
                   {"partner", s.partner}, {"step", s.step}, {"quantity", to_string(s.quantity)},
                   {"value_" + u, tidy(display(s.quantity, s.value))},
                   {"expected_" + u, tidy(display(s.quantity, s.expected))},
                   {"tolerance_" + u, tidy(display(s.quantity, s.tolerance))}, {"flagged", s.flagged}});
  }
  for (const auto& c : r.reciprocity) {
    rec.push_back({{"mechanism", c.mechanism}, {"point", c.point},
                   {"c_xy_mm_per_kN", tidy(c.c_xy_m_per_N * 1e6)}, {"c_yx_mm_per_kN", tidy(c.c_yx_m_per_N * 1e6)},
                   {"max_force_N", tidy(c.max_force_N)}, {"difference_mm", tidy(units::m_to_mm(c.difference_m))},
                   {"tolerance_mm", tidy(units::m_to_mm(c.tolerance))}, {"flagged", c.flagged}});
  }
  for (const auto& c : r.comparison) {
    cmp.push_back({{"point", c.point}, {"direction", to_string(c.direction)}, {"step", c.step},
                   {"F_N", tidy(c.force_N)}, {"oc_total_mm", tidy(units::m_to_mm(c.oc_total_m))},
                   {"sc_total_mm", tidy(units::m_to_mm(c.sc_total_m))},
                   {"sc_over_oc", tidy(c.oc_total_m > 0 ? c.sc_total_m / c.oc_total_m : 0.0)}, {"flagged", c.flagged}});
  }
  return {{"source", r.source}, {"accuracy_um", tidy(units::m_to_um(r.options.accuracy_m))},
          {"angle_accuracy_deg", tidy(units::rad_to_deg(r.options.angle_accuracy_rad()))},
          {"force_basis", r.options.nominal_forces ? "nominal" : "measured"}, {"flagged", r.flagged_count()},
          {"linearity", lin}, {"symmetry", sym}, {"reciprocity", rec}, {"oc_vs_sc", cmp}, {"skipped", r.skipped},
          {"not_applicable", r.not_applicable}};
}

constexpr int kListed = 10;  // flagged results listed per check in the text output (--json has all)

// "OC 2/150, SC 5/150": flagged / checked per mechanism (results without one are counted under "-").
template <class T>
std::string per_mechanism(const std::vector<T>& v) {
  std::vector<std::pair<std::string, std::pair<int, int>>> counts;
  for (const auto& x : v) {
    std::string m = "cells";
    if constexpr (requires { x.mechanism; }) m = x.mechanism;
    auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == m; });
    if (it == counts.end()) it = counts.insert(counts.end(), {m, {0, 0}});
    it->second.first += x.flagged;
    ++it->second.second;
  }
  std::string out;
  for (const auto& [m, c] : counts) out += fmt::format("{}{} {}/{}", out.empty() ? "" : ", ", m, c.first, c.second);
  return out.empty() ? "none" : out;
}

template <class T, class F>
void list_flagged(const std::vector<T>& v, F&& line) {
  int shown = 0, total = 0;
  for (const auto& x : v) {
    if (!x.flagged) continue;
    if (++total <= kListed) line(x), ++shown;
  }
  if (total > shown) fmt::print("    ... and {} more (--json lists every result)\n", total - shown);
}

void print_text(const DataCheckReport& r) {
  fmt::print("data check of {} (cell accuracy {:.0f} um, {:.4f} deg; forces {})\n", r.source,
             units::m_to_um(r.options.accuracy_m), units::rad_to_deg(r.options.angle_accuracy_rad()),
             r.options.nominal_forces ? "nominal" : "measured");
  fmt::print("  linearity (max |residual| of the line fit > accuracy), flagged/checked: {}\n",
             per_mechanism(r.linearity));
  list_flagged(r.linearity, [](const LinearityResult& l) {
    fmt::print("    {} {} {} {}: R2 {:.3f}, max residual {:.4f} {} > {:.4f}\n", l.mechanism, to_string(l.direction),
               l.point, to_string(l.quantity), l.fit.r_squared, display(l.quantity, l.fit.max_residual), unit(l.quantity),
               display(l.quantity, l.tolerance));
  });
  fmt::print("  symmetry about y = 0 (|cell - mirrored partner| > 2 x accuracy): {}\n", per_mechanism(r.symmetry));
  list_flagged(r.symmetry, [](const SymmetryResult& s) {
    fmt::print("    {} {} {}/{} step {} {}: {:.4f} vs mirrored {:.4f} {}\n", s.mechanism, to_string(s.direction),
               s.point, s.partner, s.step, to_string(s.quantity), display(s.quantity, s.value),
               display(s.quantity, s.expected), unit(s.quantity));
  });
  fmt::print("  reciprocity (|dx/Fy - dy/Fx| x Fmax > 2 x accuracy): {}\n", per_mechanism(r.reciprocity));
  list_flagged(r.reciprocity, [](const ReciprocityResult& c) {
    fmt::print("    {} {}: dx/Fy {:.4f} vs dy/Fx {:.4f} mm/kN, {:.4f} mm apart at {:.0f} N\n", c.mechanism, c.point,
               c.c_xy_m_per_N * 1e6, c.c_yx_m_per_N * 1e6, units::m_to_mm(c.difference_m), c.max_force_N);
  });
  fmt::print("  OC vs SC (OC total > SC total + 2 x accuracy): {}\n", per_mechanism(r.comparison));
  list_flagged(r.comparison, [](const MechanismComparison& c) {
    fmt::print("    {} {} step {}: OC {:.4f} mm > SC {:.4f} mm\n", c.point, to_string(c.direction), c.step,
               units::m_to_mm(c.oc_total_m), units::m_to_mm(c.sc_total_m));
  });
  for (const auto& why : r.not_applicable) fmt::print("  does not apply to this robot: {}\n", why);
  if (!r.skipped.empty()) fmt::print("  could not run on these data: {} (missing cells or partners; see --json)\n", r.skipped.size());
  fmt::print("{} flagged\n", r.flagged_count());
}

void run(const DataCheckCli& o) {
  const auto robot = load_robot_flag(o.robot);
  DataCheckOptions options = data_check_options(robot);
  options.accuracy_m = units::um_to_m(o.accuracy_um);
  options.nominal_forces = o.nominal_forces;
  if (o.file.empty() && robot.compliance.table.empty()) {
    throw Error(fmt::format("robot '{}' names no displacement table: give one as the first argument", robot.name));
  }
  auto table = load_displacement_table(o.file.empty() ? robot.compliance.table : table_ref(o.file));
  // A robot named on the command line selects its own rows; without one every row is checked (OC vs SC).
  if (o.robot_given) table = table.filter(robot.compliance.rows);
  if (table.rows.empty()) throw Error(SourceLocation{table.source}, "no rows with mechanism '" + robot.compliance.rows + "'");
  const auto report = check_displacements(table, options);
  o.json ? print_json(to_json(report)) : print_text(report);
}
}  // namespace

void add_data_command(CLI::App& app) {
  auto* data = app.add_subcommand("data", "Displacement data sets");
  data->require_subcommand(1);
  auto opts = std::make_shared<DataCheckCli>();
  auto* check = data->add_subcommand("check", "Linearity, symmetry, reciprocity and OC-vs-SC checks of a table");
  check->add_option("file", opts->file, "Displacement table CSV, or 'thesis' (default: the robot's own table)");
  auto* robot = add_robot_flag(check, opts->robot)
                    ->description("Robot: its rows of the table, |UL| for the angle accuracy, whether symmetry is "
                                  "expected (default: oc-gu, every row)");
  check->add_option("--accuracy-um", opts->accuracy_um, "Accuracy of one displacement cell (um)")->capture_default_str()
      ->check(within(0.001, 100000.0, "um"));
  check->add_flag("--nominal-forces", opts->nominal_forces, "Regress on the table's F_nominal_N (its round loads) instead of F_N");
  check->add_flag("--json", opts->json, "Print every result as JSON");
  check->callback([opts, robot] {
    opts->robot_given = robot->count() > 0;
    run(*opts);
  });
}

}  // namespace stiffpath::cli
