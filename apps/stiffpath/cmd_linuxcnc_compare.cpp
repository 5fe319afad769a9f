// Comparing one job's two routes through LinuxCNC: the commanded tool points at the same place of the laser path.
#include "cmd_linuxcnc_compare.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace stiffpath::cli::linuxcnc {

namespace {

// One laser-on period of a route, placed on the path.
struct PathPoint {
  int interval = 0;             // which laser-on stretch of the job (0, 1, …)
  double s_mm = 0.0;            // planned distance along that stretch
  double path_mm = 0.0;         // … plus the lengths of the stretches before it (for the figure)
  double speed_mm_s = 0.0;      // of the planned point
  double command_mm[2] = {0, 0};  // FK of the commanded joints
  double correction_um = 0.0;   // |command − planned|
};

std::vector<PathPoint> on_path(const std::vector<RecordRow>& rows, const kinematics::FiveBar& five_bar, double period_s,
                               RouteSummary& summary) {
  std::vector<PathPoint> points;
  double s = 0.0;
  int interval = -1;
  summary.duration_s = rows.empty() ? 0.0 : rows.back().t_s - rows.front().t_s + period_s;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto& r = rows[k];
    if (!r.laser) continue;
    if (k > 0 && rows[k - 1].laser) {
      s += std::hypot(r.x_mm - rows[k - 1].x_mm, r.y_mm - rows[k - 1].y_mm);
    } else {
      summary.laser_path_mm += s;
      s = 0.0;
      ++interval;
    }
    const std::size_t i0 = k > 0 ? k - 1 : k, i1 = k + 1 < rows.size() ? k + 1 : k;  // centred where there are neighbours
    PathPoint p;
    p.interval = interval;
    p.s_mm = s;
    p.path_mm = summary.laser_path_mm + s;
    p.speed_mm_s = i1 > i0 ? std::hypot(rows[i1].x_mm - rows[i0].x_mm, rows[i1].y_mm - rows[i0].y_mm) /
                                 (period_s * static_cast<double>(i1 - i0))
                           : 0.0;
    const kinematics::Vec2 c = five_bar.forward(kinematics::Vec2(r.theta_rad[0], r.theta_rad[1])) * 1e3;
    p.command_mm[0] = c.x();
    p.command_mm[1] = c.y();
    p.correction_um = 1e3 * std::hypot(c.x() - r.x_mm, c.y() - r.y_mm);
    summary.largest_correction_um = std::max(summary.largest_correction_um, p.correction_um);
    summary.laser_s += period_s;
    points.push_back(p);
  }
  summary.laser_path_mm += s;
  summary.intervals = interval + 1;
  return points;
}

// The commanded point of `route` at position s of its laser-on stretch `interval` (linear between its samples;
// clamped at the stretch's ends).
std::array<double, 2> command_at(const std::vector<PathPoint>& route, int interval, double s) {
  const auto first = std::lower_bound(route.begin(), route.end(), interval,
                                      [](const PathPoint& p, int i) { return p.interval < i; });
  const auto last = std::upper_bound(first, route.end(), interval, [](int i, const PathPoint& p) { return i < p.interval; });
  const auto after = std::lower_bound(first, last, s, [](const PathPoint& p, double v) { return p.s_mm < v; });
  if (after == first) return {after->command_mm[0], after->command_mm[1]};
  if (after == last) return {(last - 1)->command_mm[0], (last - 1)->command_mm[1]};
  const auto& b = *after;
  const auto& a = *(after - 1);
  const double f = b.s_mm > a.s_mm ? (s - a.s_mm) / (b.s_mm - a.s_mm) : 1.0;
  return {a.command_mm[0] + f * (b.command_mm[0] - a.command_mm[0]), a.command_mm[1] + f * (b.command_mm[1] - a.command_mm[1])};
}

}  // namespace

Comparison compare_routes(const std::vector<RecordRow>& linuxcnc, const std::vector<RecordRow>& stiffpath,
                          const kinematics::Robot& robot, double period_s, const std::filesystem::path& dir, bool& figure) {
  const auto five_bar = robot.five_bar();
  Comparison c;
  const std::vector<PathPoint> routes[2] = {on_path(linuxcnc, five_bar, period_s, c.routes[0]),
                                            on_path(stiffpath, five_bar, period_s, c.routes[1])};
  std::string data =
      "# path_mm speed_mm_s correction_um: LinuxCNC plans, then stiffpath plans; then path_mm difference_um. path_mm: "
      "planned distance with the laser on, the stretches one after the other\n";
  for (int r = 0; r < 2; ++r) {
    for (const auto& p : routes[r]) data += fmt::format("{:.6f} {:.3f} {:.4f}\n", p.path_mm, p.speed_mm_s, p.correction_um);
    data += "\n\n";
  }
  c.comparable = c.routes[0].intervals == c.routes[1].intervals && c.routes[0].intervals > 0;
  for (int r = 0; r < 2 && c.comparable; ++r) {
    for (const auto& p : routes[r]) {
      const auto other = command_at(routes[1 - r], p.interval, p.s_mm);
      const double d_um = 1e3 * std::hypot(p.command_mm[0] - other[0], p.command_mm[1] - other[1]);
      if (r == 0) data += fmt::format("{:.6f} {:.4f}\n", p.path_mm, d_um);
      if (d_um > c.largest_difference_um) {
        c.largest_difference_um = d_um;
        c.at_path_mm = p.s_mm;
        c.at_interval = p.interval;
      }
    }
  }
  core::write_file_atomically(dir / "compare.tsv", data);
  figure = report::gnuplot_available() && c.comparable;
  if (figure) {
    const std::string commands = fmt::format(R"(set multiplot layout 2,1 title {}
set grid
set key top right
set ylabel 'planned speed (mm/s)'
plot 'compare.tsv' index 0 using 1:2 with lines lw 2 title 'LinuxCNC plans', '' index 1 using 1:2 with lines lw 2 title 'stiffpath plans'
set xlabel 'distance travelled with the laser on (mm)'
set ylabel 'µm'
plot 'compare.tsv' index 0 using 1:3 with lines lw 2 title '|correction|, LinuxCNC plans', '' index 1 using 1:3 with lines lw 2 title '|correction|, stiffpath plans', '' index 2 using 1:2 with lines lw 2 dt 2 title 'distance between the commanded points'
unset multiplot
)",
                                             report::quote(fmt::format("one job, two routes: the commanded points differ by up to {:.1f} µm",
                                                                       c.largest_difference_um)));
    report::render(dir, report::Figure{"compare", commands, 1000, 800});
  }
  return c;
}

}  // namespace stiffpath::cli::linuxcnc
