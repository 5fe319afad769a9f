// `stiffpath repeatability FILE.csv`: ISO 9283 AP_p / RP_l per point, table 3.2's max diff, VDI/DGQ 3441.
#include <fmt/format.h>

#include <memory>

#include "commands.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/measurement/repeatability.hpp"

namespace stiffpath::cli {

namespace {
using namespace measurement;

struct RepeatabilityCli {
  std::string file;
  bool json = false;
};

double um(double m) { return tidy(units::m_to_um(m)); }

nlohmann::json to_json(const RepeatabilityReport& r, const std::string& file) {
  nlohmann::json points = nlohmann::json::array(), vdi = nlohmann::json::array();
  for (const auto& p : r.points) {
    points.push_back({{"mechanism", p.mechanism}, {"point", p.point}, {"x_mm", tidy(units::m_to_mm(p.x_m))},
                      {"y_mm", tidy(units::m_to_mm(p.y_m))}, {"trials", p.trials}, {"missing", p.missing},
                      {"ap_x_um", um(p.mean_x_m)}, {"ap_y_um", um(p.mean_y_m)}, {"ap_um", um(p.ap_m)},
                      {"l_mean_um", um(p.l_mean_m)}, {"s_l_um", um(p.s_l_m)}, {"rp_um", um(p.rp_m)},
                      {"max_diff_x_um", um(p.max_diff_x_m)}, {"max_diff_y_um", um(p.max_diff_y_m)}});
  }
  for (const auto& a : r.vdi3441) {
    nlohmann::json pts = nlohmann::json::array();
    for (const auto& p : a.points) {
      pts.push_back({{"point", p.point}, {"mean_up_um", um(p.mean_up_m)}, {"mean_down_um", um(p.mean_down_m)},
                     {"reversal_span_um", um(p.reversal_span_m)}, {"scatter_um", um(p.scatter_m)}});
    }
    vdi.push_back({{"mechanism", a.mechanism}, {"axis", std::string(1, a.axis)},
                   {"position_deviation_um", um(a.position_deviation_m)},
                   {"reversal_span_max_um", um(a.reversal_span_max_m)},
                   {"reversal_span_mean_um", um(a.reversal_span_mean_m)}, {"scatter_max_um", um(a.scatter_max_m)},
                   {"scatter_mean_um", um(a.scatter_mean_m)}, {"uncertainty_um", um(a.uncertainty_m)},
                   {"points", pts}});
  }
  return {{"source", file}, {"points", points}, {"vdi3441", vdi}, {"missing", r.missing}};
}

void print_text(const RepeatabilityReport& r) {
  fmt::print("{:<4} {:<8} {:>6} {:>9} {:>9} {:>9} {:>12} {:>12}\n", "mech", "point", "trials", "AP_p_um", "RP_l_um",
             "S_l_um", "maxdiff_x_um", "maxdiff_y_um");
  for (const auto& p : r.points) {
    fmt::print("{:<4} {:<8} {:>6} {:>9.1f} {:>9.2f} {:>9.2f} {:>12.1f} {:>12.1f}\n", p.mechanism, p.point, p.trials,
               units::m_to_um(p.ap_m), units::m_to_um(p.rp_m), units::m_to_um(p.s_l_m), units::m_to_um(p.max_diff_x_m),
               units::m_to_um(p.max_diff_y_m));
  }
  for (const auto& a : r.vdi3441) {
    fmt::print("VDI/DGQ 3441 {}axis {}: Pa {:.1f} um, U max {:.1f} / mean {:.1f} um, Ps max {:.1f} / mean {:.1f} um, "
               "P {:.1f} um\n",
               a.mechanism.empty() ? "" : a.mechanism + " ", a.axis, units::m_to_um(a.position_deviation_m), units::m_to_um(a.reversal_span_max_m),
               units::m_to_um(a.reversal_span_mean_m), units::m_to_um(a.scatter_max_m),
               units::m_to_um(a.scatter_mean_m), units::m_to_um(a.uncertainty_m));
  }
  if (r.vdi3441.empty()) fmt::print("VDI/DGQ 3441: needs an 'approach' column with + and - trials at every point\n");
  for (const auto& m : r.missing) fmt::print("missing: {}\n", m);
}

void run(const RepeatabilityCli& o) {
  const auto report = analyse_repeatability(load_trials(o.file == "thesis" ? thesis_repeatability() : core::parse_data_ref(o.file)));
  o.json ? print_json(to_json(report, o.file)) : print_text(report);
}
}  // namespace

void add_repeatability_command(CLI::App& app) {
  auto opts = std::make_shared<RepeatabilityCli>();
  auto* cmd = app.add_subcommand("repeatability", "ISO 9283 and VDI/DGQ 3441 figures from repeated positioning trials");
  cmd->add_option("file", opts->file, "Trials CSV (point,x_mm,y_mm,trial,[approach,]err_x_mm,err_y_mm), or 'thesis'")
      ->required();
  cmd->add_flag("--json", opts->json, "Print JSON (values in um)");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace stiffpath::cli
