// gnuplot figures of a results table (the twin's experiment or scanned marks) in the layout of thesis figs. 4.9–4.11.
#include "stiffpath/report/experiment_plots.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <map>

#include "stiffpath/core/atomic_file.hpp"

namespace stiffpath::report {

std::vector<std::string> write_results_figures(const std::filesystem::path& dir, const ResultsTable& table,
                                               Style style) {
  std::vector<std::string> robots;
  for (const auto& r : table.rows) {
    if (std::find(robots.begin(), robots.end(), r.robot) == robots.end()) robots.push_back(r.robot);
  }
  struct Panel {
    std::string name, motion, ylabel, what, figure;
    int column;  // in the data file: 1 acceleration_g, 2 length_mm, 3 deviation_area_mm2
  };
  const std::vector<Panel> panels{
      {"fig_4_9a_y_length", "y", "length (mm)", "length", "4.9a", 2},
      {"fig_4_9b_y_deviation", "y", "deviation area (mm²)", "deviation from linearity", "4.9b", 3},
      {"fig_4_10a_x_length", "x", "length (mm)", "length", "4.10a", 2},
      {"fig_4_10b_x_deviation", "x", "deviation area (mm²)", "deviation from linearity", "4.10b", 3},
      {"fig_4_11_triangle_deviation", "triangle", "total deviation area (mm²)", "deviation from linearity", "4.11", 3},
  };
  std::vector<std::string> rendered;
  for (const auto& panel : panels) {
    std::string data, plots;
    int block = 0;
    for (std::size_t k = 0; k < robots.size(); ++k) {
      for (bool on : {false, true}) {
        std::vector<const ResultRow*> rows;
        for (const auto& r : table.rows) {
          if (r.robot == robots[k] && r.motion == panel.motion && r.compensated == on) rows.push_back(&r);
        }
        if (rows.empty()) continue;
        std::sort(rows.begin(), rows.end(), [](auto* a, auto* b) { return a->acceleration_g < b->acceleration_g; });
        data += fmt::format("# {} {}\n# acceleration_g\tlength_mm\tdeviation_area_mm2\n", robots[k],
                            on ? "with compensation" : "without compensation");
        for (const auto* r : rows) {
          data += fmt::format("{:g}\t{:.6f}\t{:.6f}\n", r->acceleration_g, r->length_mm, r->deviation_area_mm2);
        }
        data += "\n\n";
        if (!plots.empty()) plots += ", \\\n  ";
        // Per robot a colour and a point shape (open without, filled with compensation); dashed without, solid with.
        const int point = 4 + 2 * static_cast<int>(k % 6) + (on ? 1 : 0);
        plots += fmt::format("{} index {} using 1:{} with linespoints lc {} dt {} pt {} ps 1.3 title {}",
                             quote(panel.name + ".tsv"), block++, panel.column, k + 1, on ? 1 : 2, point,
                             quote(robots[k] + (on ? " with compensation" : " without")));
      }
    }
    if (plots.empty()) continue;
    core::write_file_atomically(dir / (panel.name + ".tsv"), data);
    Figure figure;
    figure.name = panel.name;
    figure.style = style;
    figure.commands = fmt::format(
        "set title {}\nset xlabel 'path acceleration (g)'\nset ylabel {}\nset grid\nset key outside right\n"
        "set xtics 1\nset offsets 0.2, 0.2, 0, 0\nplot {}\n",
        quote(fmt::format("{} motion: {} of the {} marks (cf. fig. {})", panel.motion, panel.what, table.source,
                          panel.figure)),
        quote(panel.ylabel), plots);
    if (style == Style::paper) figure.width_px = 1100;
    render(dir, figure);
    rendered.push_back(panel.name);
  }
  return rendered;
}

}  // namespace stiffpath::report
