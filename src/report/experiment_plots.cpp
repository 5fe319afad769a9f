// gnuplot figures of the twin's test matrix in the layout of thesis figs. 4.9–4.11.
#include "stiffpath/report/experiment_plots.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <map>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {
namespace {

std::string series_file(const std::string& mechanism, bool compensated, const std::string& motion) {
  return fmt::format("experiment_{}_{}_{}.tsv", mechanism, compensated ? "on" : "off", motion);
}

}  // namespace

std::vector<std::string> write_experiment_figures(const std::filesystem::path& dir,
                                                  const std::vector<simulation::RunResult>& results) {
  std::map<std::string, std::string> files;  // file name → contents
  std::vector<std::string> mechanisms;
  for (const auto& r : results) {
    const std::string name = series_file(r.spec.robot, r.spec.compensated, r.spec.motion);
    auto& text = files[name];
    if (text.empty()) text = "# acceleration_g\tlength_mm\tdeviation_area_mm2\tmax_deviation_mm\n";
    text += fmt::format("{:g}\t{:.6f}\t{:.6f}\t{:.6f}\n", r.spec.acceleration_g, r.metrics.length_m * 1e3,
                        r.metrics.deviation_area_m2 * 1e6, r.metrics.max_deviation_m * 1e3);
    if (std::find(mechanisms.begin(), mechanisms.end(), r.spec.robot) == mechanisms.end()) {
      mechanisms.push_back(r.spec.robot);
    }
  }
  for (const auto& [name, text] : files) core::write_file_atomically(dir / name, text);

  struct Panel {
    std::string name, motion, ylabel, title;
    int column;
  };
  const std::vector<Panel> panels{
      {"fig_4_9a_y_length", "y", "length (mm)", "simulated y motion: measured length (cf. fig. 4.9a)", 2},
      {"fig_4_9b_y_deviation", "y", "deviation area (mm^2)", "simulated y motion: deviation from linearity (cf. fig. 4.9b)", 3},
      {"fig_4_10a_x_length", "x", "length (mm)", "simulated x motion: measured length (cf. fig. 4.10a)", 2},
      {"fig_4_10b_x_deviation", "x", "deviation area (mm^2)", "simulated x motion: deviation from linearity (cf. fig. 4.10b)", 3},
      {"fig_4_11_triangle_deviation", "triangle", "total deviation area (mm^2)",
       "simulated triangle: deviation from linearity (cf. fig. 4.11)", 3},
  };
  std::vector<std::string> rendered;
  for (const auto& panel : panels) {
    std::string plots;
    int colour = 1;
    for (const auto& mechanism : mechanisms) {
      for (bool on : {false, true}) {
        const std::string file = series_file(mechanism, on, panel.motion);
        if (!files.count(file)) continue;
        if (!plots.empty()) plots += ", \\\n  ";
        plots += fmt::format("{} using 1:{} with linespoints lc {} dt {} pt {} title {}", quote(file), panel.column,
                             colour, on ? 1 : 2, on ? 7 : 6, quote(mechanism + (on ? " + comp." : "")));
      }
      ++colour;
    }
    if (plots.empty()) continue;
    Figure figure;
    figure.name = panel.name;
    figure.commands = fmt::format(
        "set title {}\nset xlabel 'acceleration (g)'\nset ylabel {}\nset grid\nset key outside right\n"
        "set xtics 1\nplot {}\n",
        quote(panel.title), quote(panel.ylabel), plots);
    render(dir, figure);
    rendered.push_back(panel.name);
  }
  return rendered;
}

}  // namespace stiffpath::report
