// Geometry calibration figures with gnuplot: misfit per reading before/after, and the pose plan over the reach.
#include "stiffpath/report/geometry_plots.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "stiffpath/core/atomic_file.hpp"

namespace stiffpath::report {

void plot_geometry_residuals(const std::filesystem::path& dir, const std::string& name,
                             const calibration::GeometryFitResult& fit, const std::string& title, Style style) {
  std::string data = "# reading\tline\tbefore_um\tafter_um\n";
  int k = 0;
  for (const auto& r : fit.residuals) {
    // The log scale needs positive values: 1 nm stands for an exact fit.
    data += fmt::format("{}\t{}\t{:.4f}\t{:.4f}\n", ++k, r.line, std::max(r.before_m.norm() * 1e6, 1e-3),
                        std::max(r.after_m.norm() * 1e6, 1e-3));
  }
  core::write_file_atomically(dir / (name + ".tsv"), data);
  const double two_sigma_um = 2.0 * fit.sigma_estimated_m * 1e6;
  const std::string file = quote(name + ".tsv");
  const std::string commands = fmt::format(
      "set title {title}\nset xlabel 'reading'\nset ylabel '|measured - predicted| (µm)'\nset logscale y\n"
      "set grid\nset key top right\nset xrange [0:{n}]\n"
      "plot {file} using 1:3 with impulses lw 3 lc rgb '#c00000' title {before}, \\\n"
      "  {file} using ($1+0.25):4 with impulses lw 3 lc rgb '#0050a0' title {after}, \\\n"
      "  {two:.4f} with lines dt 2 lc rgb '#606060' title {noise}\n",
      fmt::arg("title", quote(title)), fmt::arg("n", k + 1), fmt::arg("file", file),
      fmt::arg("before", quote(fmt::format("robot file's geometry (RMS {:.1f} µm per coordinate)", fit.rms_before_m * 1e6))),
      fmt::arg("after", quote(fmt::format("calibrated (RMS {:.1f} µm)", fit.rms_after_m * 1e6))),
      fmt::arg("two", two_sigma_um), fmt::arg("noise", quote(fmt::format("2σ of the fit's residuals ({:.1f} µm)", two_sigma_um))));
  render(dir, Figure{name, commands, 1000, 600, style});
}

void plot_geometry_plan(const std::filesystem::path& dir, const std::string& name, const calibration::GeometryPlan& plan,
                        const kinematics::Robot& robot, const std::string& title, Style style) {
  std::string data = "# reachable lattice (x_mm, y_mm)\n";
  for (const auto& p : plan.reachable) data += fmt::format("{:.3f}\t{:.3f}\n", p.x() * 1e3, p.y() * 1e3);
  data += "\n\n# actuators (x_mm, y_mm)\n";
  for (const auto& a : robot.geometry.actuator_m) data += fmt::format("{:.3f}\t{:.3f}\n", a.x() * 1e3, a.y() * 1e3);
  data += "\n\n# poses in measuring order (x_mm, y_mm, number)\n";
  int k = 0;
  for (const auto& p : plan.poses) data += fmt::format("{:.3f}\t{:.3f}\t{}\n", p.p_m.x() * 1e3, p.p_m.y() * 1e3, ++k);
  core::write_file_atomically(dir / (name + ".tsv"), data);
  const std::string file = quote(name + ".tsv");
  const std::string commands = fmt::format(
      "set title {title}\nset xlabel 'x (mm)'\nset ylabel 'y (mm)'\nset size ratio -1\nset grid\nset key outside bottom center horizontal\n"
      "plot {file} index 0 using 1:2 with points pt 7 ps 0.3 lc rgb '#c8c8c8' title {reach}, \\\n"
      "  {file} index 1 using 1:2 with points pt 5 ps 1.5 lc rgb 'black' title 'actuators', \\\n"
      "  {file} index 2 using 1:2 with linespoints pt 7 ps 1.2 lw 1 dt 3 lc rgb '#c00000' title 'poses, in measuring order', \\\n"
      "  {file} index 2 using 1:2:3 with labels offset 0.9,0.6 font ',9' notitle\n",
      fmt::arg("title", quote(title)), fmt::arg("file", file),
      fmt::arg("reach", quote(fmt::format("candidates: reachable within the joint limits, condition number <= {:g} ({:.1f} mm "
                                          "lattice)",
                                          plan.max_condition_number, plan.lattice_step_m * 1e3))));
  render(dir, Figure{name, commands, 900, 900, style});
}

}  // namespace stiffpath::report
