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

// Distance (mm) from `point` to the segment a–b.
double to_segment(const double point[2], const double a[2], const double b[2]) {
  const double dx = b[0] - a[0], dy = b[1] - a[1], length2 = dx * dx + dy * dy;
  double f = length2 > 0.0 ? ((point[0] - a[0]) * dx + (point[1] - a[1]) * dy) / length2 : 0.0;
  f = std::clamp(f, 0.0, 1.0);
  return std::hypot(point[0] - (a[0] + f * dx), point[1] - (a[1] + f * dy));
}

// Distance (mm) from the commanded point `p` to the other route's commanded path: the polyline of its commanded
// points in the same laser-on stretch whose planned position lies within kWindow_mm of p's (plus the samples just
// outside, so that the window's edge segments count). Where the robot stands at a corner the command still moves
// (the correction changes with the acceleration), so the comparison is of the paths drawn, not of points at one s.
double distance_to_route(const std::vector<PathPoint>& route, const PathPoint& p) {
  constexpr double kWindow_mm = 1.0;
  const auto first = std::lower_bound(route.begin(), route.end(), p.interval,
                                      [](const PathPoint& q, int i) { return q.interval < i; });
  const auto last = std::upper_bound(first, route.end(), p.interval, [](int i, const PathPoint& q) { return i < q.interval; });
  if (first == last) return 0.0;
  auto lo = std::lower_bound(first, last, p.s_mm - kWindow_mm, [](const PathPoint& q, double v) { return q.s_mm < v; });
  auto hi = std::upper_bound(lo, last, p.s_mm + kWindow_mm, [](double v, const PathPoint& q) { return v < q.s_mm; });
  if (lo != first) --lo;
  if (hi != last) ++hi;
  double best = std::hypot(p.command_mm[0] - lo->command_mm[0], p.command_mm[1] - lo->command_mm[1]);
  for (auto q = lo; q + 1 < hi; ++q) best = std::min(best, to_segment(p.command_mm, q->command_mm, (q + 1)->command_mm));
  return best;
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
      const double d_um = 1e3 * distance_to_route(routes[1 - r], p);
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
plot 'compare.tsv' index 0 using 1:3 with lines lw 2 title '|correction|, LinuxCNC plans', '' index 1 using 1:3 with lines lw 2 title '|correction|, stiffpath plans', '' index 2 using 1:2 with lines lw 2 dt 2 title 'distance to the other route''s commanded path'
unset multiplot
)",
                                             report::quote(fmt::format("one job, two routes: the commanded tool paths lie up to {:.1f} µm apart",
                                                                       c.largest_difference_um)));
    report::render(dir, report::Figure{"compare", commands, 1000, 800});
  }
  return c;
}

}  // namespace stiffpath::cli::linuxcnc
