// gnuplot figures of a results table (the twin's experiment or scanned marks) in the layout of thesis figs. 4.9–4.11.
#include "stiffpath/report/experiment_plots.hpp"

#include <algorithm>
#include <cctype>
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
  // Without compensation first, then each compensation variant in the order the table names them.
  struct Series {
    bool compensated;
    std::string variant;
    [[nodiscard]] std::string label() const {
      if (!compensated) return "without";
      return variant.empty() ? "with compensation" : "with " + variant + " compensation";
    }
  };
  std::vector<Series> series{{false, ""}};
  for (const auto& r : table.rows) {
    if (!r.compensated) continue;
    if (std::none_of(series.begin(), series.end(), [&](const Series& s) { return s.compensated && s.variant == r.variant; })) {
      series.push_back({true, r.variant});
    }
  }
  struct Panel {
    std::string name, motion, ylabel, what, figure;
    int column;  // in the data file: 1 acceleration_g, 2 length_mm, 3 deviation_area_mm2
  };
  std::vector<Panel> panels{
      {"fig_4_9a_y_length", "y", "length (mm)", "length", "4.9a", 2},
      {"fig_4_9b_y_deviation", "y", "deviation area (mm²)", "deviation from linearity", "4.9b", 3},
      {"fig_4_10a_x_length", "x", "length (mm)", "length", "4.10a", 2},
      {"fig_4_10b_x_deviation", "x", "deviation area (mm²)", "deviation from linearity", "4.10b", 3},
      {"fig_4_11_triangle_deviation", "triangle", "total deviation area (mm²)", "deviation from linearity", "4.11", 3},
  };
  // Every other motion (off-grid motions, a user's paths) gets the same two panels, in the table's order.
  for (const auto& r : table.rows) {
    if (std::any_of(panels.begin(), panels.end(), [&](const Panel& p) { return p.motion == r.motion; })) continue;
    std::string stem;
    for (const char c : r.motion) stem += std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' ? c : '_';
    panels.push_back({"results_" + stem + "_length", r.motion, "length (mm)", "length", "", 2});
    panels.push_back({"results_" + stem + "_deviation", r.motion, "total deviation area (mm²)", "deviation from linearity", "", 3});
  }
  std::vector<std::string> rendered;
  for (const auto& panel : panels) {
    std::string data, plots;
    int block = 0;
    for (std::size_t k = 0; k < robots.size(); ++k) {
      for (std::size_t v = 0; v < series.size(); ++v) {
        const Series& one = series[v];
        std::vector<const ResultRow*> rows;
        for (const auto& r : table.rows) {
          if (r.robot == robots[k] && r.motion == panel.motion && r.compensated == one.compensated &&
              r.variant == one.variant) {
            rows.push_back(&r);
          }
        }
        if (rows.empty()) continue;
        std::sort(rows.begin(), rows.end(), [](auto* a, auto* b) { return a->acceleration_g < b->acceleration_g; });
        const std::string title = robots[k] + " " + one.label();
        data += fmt::format("# {}\n# acceleration_g\tlength_mm\tdeviation_area_mm2\n", title);
        for (const auto* r : rows) {
          data += fmt::format("{:g}\t{:.6f}\t{:.6f}\n", r->acceleration_g, r->length_mm, r->deviation_area_mm2);
        }
        data += "\n\n";
        if (!plots.empty()) plots += ", \\\n  ";
        // Per robot a colour, per compensation a point shape (open without, filled with) and a dash pattern
        // (dashed without, solid with the first variant, dotted and further with the others).
        const int point = 4 + 2 * static_cast<int>(k % 6) + (one.compensated ? 1 : 0);
        const int dash = one.compensated ? (v == 1 ? 1 : static_cast<int>(v) + 1) : 2;
        plots += fmt::format("{} index {} using 1:{} with linespoints lc {} dt {} pt {} ps 1.3 title {}",
                             quote(panel.name + ".tsv"), block++, panel.column, k + 1, dash, point, quote(title));
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
        quote(fmt::format("{} motion: {} of the {} marks{}", panel.motion, panel.what, table.source,
                          panel.figure.empty() ? "" : " (cf. fig. " + panel.figure + ")")),
        quote(panel.ylabel), plots);
    if (style == Style::paper) figure.width_px = 1100;
    render(dir, figure);
    rendered.push_back(panel.name);
  }
  return rendered;
}

}  // namespace stiffpath::report
