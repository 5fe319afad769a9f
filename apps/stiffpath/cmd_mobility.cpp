// `stiffpath mobility`: Grübler–Kutzbach mobility of the thesis's three linkages (eqs. 3.1–3.2).
#include <fmt/format.h>
#include <memory>
#include <numeric>

#include "commands.hpp"
#include "stiffpath/kinematics/mobility.hpp"

namespace stiffpath::cli {

void add_mobility_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("mobility", "Mobility (eq. 3.1) of the 6R, SC and OC linkages (eq. 3.2)");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json, "Print JSON");
  cmd->callback([json] {
    nlohmann::json cases = nlohmann::json::array();
    for (const auto& linkage : kinematics::thesis_linkages()) {
      const int m = kinematics::gruebler_kutzbach(linkage);
      const int real = kinematics::actual_mobility(linkage);
      const int joints = static_cast<int>(linkage.joint_freedoms.size());
      const int freedoms = std::accumulate(linkage.joint_freedoms.begin(), linkage.joint_freedoms.end(), 0);
      if (*json) {
        cases.push_back({{"name", linkage.name},
                         {"links", linkage.links},
                         {"joints", joints},
                         {"gruebler_kutzbach", m},
                         {"actual_mobility", real},
                         {"note", linkage.note}});
      } else {
        fmt::print("{:<28} M = {}({} - {} - 1) + {} = {:>2}   moves with {} DoF\n    {}\n", linkage.name,
                   linkage.space_dof, linkage.links, joints, freedoms, m, real, linkage.note);
      }
    }
    if (*json) print_json(cases);
  });
}

}  // namespace stiffpath::cli
