// plot_mark: nearest-segment deviations of a mark from its commanded polyline, magnified, with a scale bar.
#include "stiffpath/report/mark_plots.hpp"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::report {
namespace {
using V = Eigen::Vector2d;

// Every k-th point (and the last), so at most `max` remain.
std::vector<V> thin(const std::vector<V>& points, std::size_t max) {
  if (points.size() <= max) return points;
  const std::size_t step = (points.size() + max - 1) / max;
  std::vector<V> out;
  for (std::size_t k = 0; k < points.size(); k += step) out.push_back(points[k]);
  if ((points.size() - 1) % step != 0) out.push_back(points.back());
  return out;
}

// The smallest 1-2-5 value ≥ x.
double nice(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * decade >= x * (1 - 1e-12)) return m * decade;
  }
  return 10 * decade;
}

struct Nearest {
  V foot;
  double signed_m;
};

Nearest nearest(const std::vector<V>& path, const V& p) {
  Nearest best{path.front(), 0.0};
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    const V a = path[k], ab = path[k + 1] - a;
    const double len2 = ab.squaredNorm();
    // A repeated point (the robot at rest, a smoothed start) has no direction, so no side: skipped.
    if (len2 == 0.0) continue;
    const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
    const V foot = a + t * ab;
    const double d2 = (p - foot).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      const double cross = ab.x() * (p - a).y() - ab.y() * (p - a).x();
      best = {foot, cross >= 0 ? std::sqrt(d2) : -std::sqrt(d2)};
    }
  }
  return best;
}
}  // namespace

MarkPlotSummary plot_mark(const std::filesystem::path& dir, const std::string& name, const MarkPlotInput& input,
                          Style style, double magnification) {
  if (input.commanded_m.size() < 2) throw Error(SourceLocation{input.label}, "the commanded path has fewer than two laser-on points");
  if (input.mark_m.size() < 2) throw Error(SourceLocation{input.label}, "the mark has fewer than two points");
  const std::vector<V> path = thin(input.commanded_m, 5000), mark = thin(input.mark_m, 5000);
  V lo = path.front(), hi = path.front();
  for (const V& p : path) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if ((hi - lo).maxCoeff() == 0.0) throw Error(SourceLocation{input.label}, "the commanded path does not move while the laser is on");
  const double extent = std::max((hi - lo).maxCoeff(), 1e-3);

  std::vector<Nearest> near;
  MarkPlotSummary s;
  double sum2 = 0.0;
  for (const V& p : mark) {
    near.push_back(nearest(path, p));
    s.max_deviation_um = std::max(s.max_deviation_um, std::abs(near.back().signed_m) * 1e6);
    sum2 += near.back().signed_m * near.back().signed_m;
  }
  s.rms_deviation_um = std::sqrt(sum2 / static_cast<double>(mark.size())) * 1e6;
  s.magnification = magnification > 0 ? magnification
                    : s.max_deviation_um > 0 ? nice(0.04 * extent / (s.max_deviation_um * 1e-6))
                                             : 1.0;
  s.scale_bar_um = nice(std::max(s.max_deviation_um, 1e-3) / 2.0);

  std::string data = fmt::format("# {}: commanded path (x_mm, y_mm)\n", input.label);
  for (const V& p : path) data += fmt::format("{:.6f}\t{:.6f}\n", p.x() * 1e3, p.y() * 1e3);
  data += fmt::format("\n\n# {} mark, deviation x{:g} (x_mm, y_mm)\n", input.source, s.magnification);
  for (std::size_t k = 0; k < mark.size(); ++k) {
    const V shown = near[k].foot + s.magnification * (mark[k] - near[k].foot);
    data += fmt::format("{:.6f}\t{:.6f}\n", shown.x() * 1e3, shown.y() * 1e3);
  }
  data += "\n\n# arc length along the mark (mm), signed deviation (um)\n";
  double arc = 0.0;
  for (std::size_t k = 0; k < mark.size(); ++k) {
    if (k > 0) arc += (mark[k] - mark[k - 1]).norm();
    data += fmt::format("{:.6f}\t{:.4f}\n", arc * 1e3, near[k].signed_m * 1e6);
  }
  core::write_file_atomically(dir / (name + ".tsv"), data);

  // Scale bar below the path: scale_bar_um of deviation drawn at the magnification, in mm on the plot.
  const double bar_mm = s.scale_bar_um * 1e-3 * s.magnification;
  const double bx = lo.x() * 1e3, by = lo.y() * 1e3 - 0.08 * extent * 1e3;
  const std::string file = quote(name + ".tsv");
  const std::string commands = fmt::format(
      "set multiplot layout 2,1 title {title}\n"
      "set size ratio -1\nset grid\nset key outside right top\nset xtics rotate by 90 right\nset xlabel 'x (mm)'\nset ylabel 'y (mm)'\n"
      "set offsets graph 0.05, graph 0.05, graph 0.12, graph 0.05\n"
      "set arrow 1 from {bx:.4f},{by:.4f} to {bx2:.4f},{by:.4f} heads size screen 0.006,90 lw 2 lc rgb 'black'\n"
      "set label 1 {bar} at {bx:.4f},{by:.4f} offset 0,-1 left\n"
      "plot {file} index 0 using 1:2 with lines lt 1 dt 2 lw 1.5 lc rgb '#606060' title 'commanded path', \\\n"
      "  {file} index 1 using 1:2 with lines lt 1 lw 1.5 lc rgb '#c00000' title {mark}\n"
      "unset arrow\nunset label\nset xtics norotate\nset size noratio\nset offsets 0,0,0,0\n"
      "set xlabel 'arc length along the mark (mm)'\nset ylabel 'deviation (µm), left positive'\n"
      "plot {file} index 2 using 1:2 with lines lw 1.5 lc rgb '#c00000' title {mark2}, 0 with lines dt 2 lc rgb '#606060' notitle\n"
      "unset multiplot\n",
      fmt::arg("title", quote(fmt::format("{}: {} mark over the commanded path (max deviation {:.1f} µm, RMS {:.1f} µm)",
                                          input.label, input.source, s.max_deviation_um, s.rms_deviation_um))),
      fmt::arg("bx", bx), fmt::arg("by", by), fmt::arg("bx2", bx + bar_mm),
      fmt::arg("bar", quote(fmt::format("{:g} µm of deviation (x{:g})", s.scale_bar_um, s.magnification))),
      fmt::arg("file", file), fmt::arg("mark", quote(fmt::format("{} mark, deviation x{:g}", input.source, s.magnification))),
      fmt::arg("mark2", quote(input.source + " mark")));
  render(dir, Figure{name, commands, 1000, 1100, style});
  return s;
}

}  // namespace stiffpath::report
