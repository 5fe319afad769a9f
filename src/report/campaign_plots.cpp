// Campaign plan figure with gnuplot: usable region and points, and the plan's predicted uncertainty over its rectangle.
#include "stiffpath/report/campaign_plots.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stiffpath/core/atomic_file.hpp"

namespace stiffpath::report {

void plot_campaign_plan(const std::filesystem::path& dir, const std::string& name, const calibration::CampaignPlan& plan,
                        const std::vector<kinematics::Vec2>& usable, const std::vector<calibration::CampaignMapPoint>& map,
                        const std::string& title, Style style) {
  std::string data = "# usable lattice (x_mm, y_mm)\n";
  for (const auto& p : usable) data += fmt::format("{:.3f}\t{:.3f}\n", p.x() * 1e3, p.y() * 1e3);
  const auto& r = plan.region;
  data += fmt::format("\n\n# region (x_mm, y_mm)\n{0:.3f}\t{2:.3f}\n{1:.3f}\t{2:.3f}\n{1:.3f}\t{3:.3f}\n{0:.3f}\t{3:.3f}\n{0:.3f}\t{2:.3f}\n",
                      r.x_min * 1e3, r.x_max * 1e3, r.y_min * 1e3, r.y_max * 1e3);
  data += "\n\n# points (x_mm, y_mm, number)\n";
  int k = 0;
  for (const auto& p : plan.points) data += fmt::format("{:.3f}\t{:.3f}\t{}\n", p.x() * 1e3, p.y() * 1e3, ++k);
  core::write_file_atomically(dir / (name + ".tsv"), data);
  std::string m;
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(map.size()))));
  for (std::size_t i = 0; i < map.size(); ++i) {
    m += fmt::format("{:.3f}\t{:.3f}\t{:.4f}\t{:.5f}\n", map[i].p.x() * 1e3, map[i].p.y() * 1e3, map[i].physical_sigma_m * 1e6,
                     map[i].interpolation_relative);
    if (n > 0 && (i + 1) % static_cast<std::size_t>(n) == 0) m += "\n";
  }
  core::write_file_atomically(dir / (name + "_map.tsv"), m);
  const std::string file = quote(name + ".tsv"), mapf = quote(name + "_map.tsv");
  const std::string palette = style == Style::paper ? "set palette defined (0 'white', 1 '#8c8c8c')\n" : "set palette rgb 33,13,10\n";
  const std::string commands = fmt::format(
      "set multiplot layout 1,3 title {title}\n"
      "set size ratio -1\nset xlabel 'x (mm)'\nset ylabel 'y (mm)'\nset key outside bottom center vertical\n"
      "set title 'usable region and the plan'\n"
      "plot {file} index 0 using 1:2 with points pt 7 ps 0.25 lc rgb '#c8c8c8' title 'usable (reach, margin, limits)', \\\n"
      "  {file} index 1 using 1:2 with lines lw 2 lc rgb 'black' title 'modelled region', \\\n"
      "  {file} index 2 using 1:2 with points pt 7 ps 1.2 lc rgb '#c00000' title 'points'\n"
      "set view map\n{palette}unset key\n"
      "set title {phys}\n"
      "splot {map} using 1:2:3 with pm3d notitle, {file} index 2 using 1:2:(0) with points pt 7 ps 1.0 lc rgb 'black' notitle\n"
      "set title 'residual spline: interpolation variance / grid mean'\n"
      "splot {map} using 1:2:4 with pm3d notitle, {file} index 2 using 1:2:(0) with points pt 7 ps 1.0 lc rgb 'black' notitle\n"
      "unset multiplot\n",
      fmt::arg("title", quote(title)), fmt::arg("file", file), fmt::arg("map", mapf), fmt::arg("palette", palette),
      fmt::arg("phys", quote(fmt::format("physical model: sigma at {:g} N (um)", plan.loads_N.back()))));
  render(dir, Figure{name, commands, 1800, 700, style});
}

}  // namespace stiffpath::report
