// plot_calibration_misfit: the plate's marks against the tip model's prediction, before and after identification.
#include "stiffpath/report/calibration_plots.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::report {

bool plot_calibration_misfit(const std::filesystem::path& dir, const std::string& name,
                             const calibration::Identification& id, Style style) {
  if (id.marks.empty()) throw Error("calibration report: no mark to draw");
  // The marks laid end to end, 1 mm apart, so that every mark has its own stretch of the axis.
  std::string data = "# mark\tarc_mm\tplot_mm\tbefore_um\tafter_um\n";
  std::string labels;
  double offset_mm = 0.0, worst_um = 0.0;
  int index = 0;
  for (const auto& m : id.marks) {
    data += fmt::format("# {}\n", m.id);
    double last = 0.0;
    for (std::size_t k = 0; k < m.s_m.size(); ++k) {
      const double s_mm = m.s_m[k] * 1e3;
      data += fmt::format("{}\t{:.4f}\t{:.4f}\t{:.3f}\t{:.3f}\n", m.id, s_mm, offset_mm + s_mm,
                          m.deviation_before_m[k] * 1e6, m.deviation_after_m[k] * 1e6);
      worst_um = std::max({worst_um, std::abs(m.deviation_before_m[k]) * 1e6, std::abs(m.deviation_after_m[k]) * 1e6});
      last = s_mm;
    }
    data += "\n\n";
    if (index % 4 == 0) labels += fmt::format("set label {} {} at {:.3f}, graph 0.97 left rotate by 90 font ',8'\n", index + 1,
                                              quote(m.id), offset_mm);
    offset_mm += last + 1.0;
    ++index;
  }
  core::write_file_atomically(dir / (name + ".tsv"), data);
  if (!gnuplot_available()) return false;
  const std::string file = quote(name + ".tsv");
  const std::string commands = fmt::format(
      "set title {title}\nset grid\nset key outside right top\n"
      "set xlabel 'the plate''s marks one after another: arc length along each (mm)'\n"
      "set ylabel 'measured minus predicted, across the mark (µm)'\nset yrange [{lo:.1f}:{hi:.1f}]\n{labels}"
      "plot {file} using 3:4 with lines lw 1 lc rgb '#a0a0a0' title 'before (the robot file)', \\\n"
      "  {file} using 3:5 with lines lw 1.5 lc rgb '#c00000' title 'after (identified)', \\\n"
      "  0 with lines dt 2 lc rgb '#404040' notitle\n",
      fmt::arg("title", quote(fmt::format("calibration plate: misfit {:.1f} µm rms before, {:.1f} µm after",
                                          id.rms_before_m * 1e6, id.rms_after_m * 1e6))),
      fmt::arg("lo", -1.1 * worst_um), fmt::arg("hi", 1.25 * worst_um), fmt::arg("labels", labels), fmt::arg("file", file));
  render(dir, Figure{name, commands, 1400, 700, style});
  return true;
}

}  // namespace stiffpath::report
