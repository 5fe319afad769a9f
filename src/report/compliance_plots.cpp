// Compliance heat maps and cross-validation scatter plots, rendered with gnuplot.
#include "stiffpath/report/compliance_plots.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::report {

double plot_compliance_map(const std::filesystem::path& dir, const std::string& name, const compliance::Model& model,
                           const std::string& title, double margin_m, Style style) {
  const auto b = model.bounds();
  const double x0 = b.x_min - margin_m, x1 = b.x_max + margin_m, y0 = b.y_min - margin_m, y1 = b.y_max + margin_m;
  std::string map, axes;
  double largest = 0.0;
  const int nx = 60, ny = 90;
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      const compliance::Vec2 p{x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny};
      const Eigen::SelfAdjointEigenSolver<compliance::Mat2> eig(0.5 * (model.compliance(p) + model.compliance(p).transpose()));
      const double lambda = eig.eigenvalues()(1) * 1e6;
      largest = std::max(largest, lambda);
      map += fmt::format("{:.4f}\t{:.4f}\t{:.6f}\n", p.x() * 1e3, p.y() * 1e3, lambda);
      if (i % 10 == 0 && j % 15 == 0) {
        for (int k = 0; k < 2; ++k) {
          const compliance::Vec2 v = eig.eigenvectors().col(k) * std::abs(eig.eigenvalues()(k)) * 1e6;
          axes += fmt::format("{:.4f}\t{:.4f}\t{:.6f}\t{:.6f}\n", p.x() * 1e3, p.y() * 1e3, v.x(), v.y());
        }
      }
    }
    map += "\n";
  }
  core::write_file_atomically(dir / (name + ".tsv"), map);
  core::write_file_atomically(dir / (name + "_axes.tsv"), axes);
  // Arrows: ±v·s with s chosen so that the largest principal compliance spans 8 mm on the plot.
  const double scale = largest > 0 ? 8.0 / largest : 1.0;
  Figure fig{name,
             fmt::format("set title {}\nset xlabel 'x (mm)'\nset ylabel 'y (mm)'\nset size ratio -1\n"
                         "unset key\nset cblabel 'largest compliance eigenvalue (µm/N)'\nset view map\n{}"
                         "set label 1 'bars: principal directions, length ∝ compliance' at screen 0.5,0.025 center\n"
                         "set xrange [{}:{}]\nset yrange [{}:{}]\n"
                         "splot {} using 1:2:3 with pm3d notitle, \\\n"
                         "  {} using ($1-$3*{s}):($2-$4*{s}):(0):($3*2*{s}):($4*2*{s}):(0) with vectors nohead lw 2 "
                         "lc rgb 'black' notitle",
                         quote(title),
                         style == Style::paper ? "set palette defined (0 'white', 1 '#8c8c8c')\n"
                                               : "set palette rgb 33,13,10\n",
                         x0 * 1e3, x1 * 1e3, y0 * 1e3, y1 * 1e3, quote(name + ".tsv"),
                         quote(name + "_axes.tsv"), fmt::arg("s", scale)),
             900, 700, style};
  render(dir, fig);
  return largest;
}

void plot_cross_validation(const std::filesystem::path& dir, const std::string& name,
                           const compliance::CvReport& report, Style style) {
  std::string data;
  for (std::size_t m = 0; m < report.methods.size(); ++m) {
    data += "# " + std::string(core::enum_name(report.methods[m].method)) + "\n";
    for (const auto& p : report.methods[m].points) {
      for (const auto& load : p.loads) {
        if (load.dx_m) data += fmt::format("{:.3f}\t{:.3f}\tx\t{}\n", *load.dx_m * 1e6, load.predicted_m.x() * 1e6, p.id);
        if (load.dy_m) data += fmt::format("{:.3f}\t{:.3f}\ty\t{}\n", *load.dy_m * 1e6, load.predicted_m.y() * 1e6, p.id);
      }
    }
    data += "\n\n";
  }
  core::write_file_atomically(dir / (name + ".tsv"), data);
  std::string commands = fmt::format("set multiplot layout 2,3 title {}\nset size square\n",
                                     quote(fmt::format("{} ({}): leave-one-out, measured vs predicted at the highest "
                                                       "load",
                                                       report.robot, report.source)));
  for (std::size_t m = 0; m < report.methods.size(); ++m) {
    const auto& method = report.methods[m];
    commands += fmt::format(
        "set title {}\nset xlabel 'measured (µm)'\nset ylabel 'predicted (µm)'\nset key top left\n"
        "plot x with lines lc rgb 'gray' notitle, {} index {} using 1:(strcol(3) eq 'x' ? $2 : 1/0) with points pt 7 "
        "title 'dx', '' index {} using 1:(strcol(3) eq 'y' ? $2 : 1/0) with points pt 5 title 'dy'\n",
        quote(fmt::format("{}: mean {:.1f} µm over {} points", core::enum_name(method.method), method.mean_um, method.predicted)),
        quote(name + ".tsv"), m, m);
  }
  commands += "unset multiplot";
  render(dir, Figure{name, commands, 1350, 900, style});
}

}  // namespace stiffpath::report
