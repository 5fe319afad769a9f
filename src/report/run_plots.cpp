// plot_run: one streaming pass over a joint file, bounded buckets of peak values, two gnuplot figures.
#include "stiffpath/report/run_plots.hpp"

#include <array>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_reader.hpp"

namespace stiffpath::report {
namespace {

using Vec2 = Eigen::Vector2d;

// Plotted series, in the data file's column order after t_s (column 1).
enum Col {
  x_mm, y_mm, xcmd_mm, ycmd_mm, speed_mm_s, speedcmd_mm_s, acc_m_s2, acccmd_m_s2, jerk_m_s3, jerkcmd_m_s3, fx_N, fy_N,
  dx_um, dy_um, cx_um, cy_um, theta1_rad, theta2_rad, omega1_rad_s, omega2_rad_s, alpha1_rad_s2, alpha2_rad_s2,
  power_pct, kCols
};
constexpr const char* kNames[kCols] = {
    "x_mm", "y_mm", "xcmd_mm", "ycmd_mm", "speed_mm_s", "speed_cmd_mm_s", "acc_m_s2", "acc_cmd_m_s2", "jerk_m_s3",
    "jerk_cmd_m_s3", "fx_N", "fy_N", "deflection_x_um", "deflection_y_um", "correction_x_um", "correction_y_um",
    "theta1_rad", "theta2_rad", "omega1_rad_s", "omega2_rad_s", "alpha1_rad_s2", "alpha2_rad_s2", "power_pct"};

using Row = std::array<double, kCols>;
struct Bucket {
  double t_s = 0.0;
  Row v{};
};

// Keeps, per column, the value of largest magnitude.
void absorb(Row& into, const Row& other) {
  for (int c = 0; c < kCols; ++c) {
    if (std::abs(other[c]) > std::abs(into[c])) into[c] = other[c];
  }
}

// Buckets of `stride` samples; when there are 2·max of them, neighbours merge and the stride doubles.
class Decimator {
 public:
  explicit Decimator(std::size_t max) : max_(std::max<std::size_t>(max, 16)) {}
  void add(double t_s, const Row& row) {
    if (filled_ == 0) buckets_.push_back({t_s, row});
    else absorb(buckets_.back().v, row);
    if (++filled_ == stride_) filled_ = 0;
    if (buckets_.size() > 2 * max_ && filled_ == 0) {
      std::vector<Bucket> merged;
      for (std::size_t k = 0; k < buckets_.size(); k += 2) {
        merged.push_back(buckets_[k]);
        if (k + 1 < buckets_.size()) absorb(merged.back().v, buckets_[k + 1].v);
      }
      buckets_ = std::move(merged);
      stride_ *= 2;
    }
  }
  [[nodiscard]] const std::vector<Bucket>& buckets() const { return buckets_; }

 private:
  std::size_t max_, stride_ = 1, filled_ = 0;
  std::vector<Bucket> buckets_;
};

struct Marker {
  double t_s;
  int line;
};

std::string markers(const std::vector<Marker>& all, int max, bool labels) {
  std::string out;
  if (all.empty() || max <= 0) return out;
  const std::size_t step = (all.size() + static_cast<std::size_t>(max) - 1) / static_cast<std::size_t>(max);
  int id = 1;
  for (std::size_t k = 0; k < all.size(); k += step) {
    out += fmt::format("set arrow {} from {:.6f}, graph 0 to {:.6f}, graph 1 nohead dt 3 lw 0.6 lc rgb '#909090'\n", id,
                       all[k].t_s, all[k].t_s);
    if (labels) {
      out += fmt::format("set label {} 'N{}' at {:.6f}, graph 1.04 rotate by 90 left font ',8' tc rgb '#606060'\n", id,
                         all[k].line, all[k].t_s);
    }
    ++id;
  }
  return out;
}

std::string series(int col, const std::string& title, int lt, int dt) {
  return fmt::format("'__DATA__' using 1:{} with lines lt {} dt {} lw 1.4 title {}", col + 2, lt, dt, quote(title));
}

std::string panel(const std::string& ylabel, const std::vector<std::string>& plots, const std::string& marks,
                  bool last) {
  std::string out = "unset arrow\nunset label\n" + marks;
  out += fmt::format("set ylabel {}\n", quote(ylabel));
  out += last ? "set xlabel 't (s)'\nset format x '%g'\n" : "unset xlabel\nset format x ''\n";
  out += "plot ";
  for (std::size_t k = 0; k < plots.size(); ++k) out += (k ? ", \\\n  " : "") + plots[k];
  return out + "\n";
}

std::string with_data(std::string text, const std::string& file) {
  const std::string token = "'__DATA__'", q = quote(file);
  for (std::size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + q.size())) {
    text.replace(at, token.size(), q);
  }
  return text;
}

}  // namespace

RunPlotSummary plot_run(const std::filesystem::path& dir, const std::string& name, const std::string& joints,
                        const RunPlotOptions& options) {
  if (!(options.gain > 0.0) && !(options.gain == 0.0)) throw Error("plot run: the gain must be 0 or positive");
  job::JointReader reader(joints);
  Decimator decimated(options.max_points);
  std::vector<Marker> lines;
  RunPlotSummary s;
  bool file_has_deflection = false, file_has_alpha = false;
  compensation::JointCommand prev;
  double t0 = 0.0;
  std::array<Vec2, 2> v_prev{Vec2::Zero(), Vec2::Zero()}, a_prev{Vec2::Zero(), Vec2::Zero()};
  Vec2 omega_prev = Vec2::Zero();
  while (const auto c = reader.next()) {
    if (s.samples == 0) t0 = c->t_s;
    Row row{};
    const std::array<Vec2, 2> p{c->target_m, c->command_m};
    std::array<Vec2, 2> v{Vec2::Zero(), Vec2::Zero()}, a{Vec2::Zero(), Vec2::Zero()}, j{Vec2::Zero(), Vec2::Zero()};
    Vec2 alpha = c->qdd_rad_s2;
    if (s.samples > 0) {
      const double dt = c->t_s - prev.t_s;
      if (!(dt > 0.0)) throw Error(SourceLocation{joints}, fmt::format("sample {}: time does not increase ({} s after "
                                                                       "{} s)", s.samples + 1, c->t_s, prev.t_s));
      const std::array<Vec2, 2> before{prev.target_m, prev.command_m};
      for (int k = 0; k < 2; ++k) {
        v[k] = (p[k] - before[k]) / dt;
        if (s.samples > 1) a[k] = (v[k] - v_prev[k]) / dt;
        if (s.samples > 2) j[k] = (a[k] - a_prev[k]) / dt;
      }
      if (!file_has_alpha) alpha = (c->qd_rad_s - omega_prev) / dt;
    }
    file_has_alpha = file_has_alpha || c->qdd_rad_s2.squaredNorm() > 0.0;
    file_has_deflection = file_has_deflection || c->deflection_m.squaredNorm() > 0.0;
    const Vec2 correction = c->command_m - c->target_m;
    const Vec2 deflection = file_has_deflection ? c->deflection_m
                            : options.gain > 0.0 ? Vec2(-correction / options.gain)
                                                 : Vec2::Zero();
    row[x_mm] = p[0].x() * 1e3, row[y_mm] = p[0].y() * 1e3, row[xcmd_mm] = p[1].x() * 1e3, row[ycmd_mm] = p[1].y() * 1e3;
    row[speed_mm_s] = v[0].norm() * 1e3, row[speedcmd_mm_s] = v[1].norm() * 1e3;
    row[acc_m_s2] = a[0].norm(), row[acccmd_m_s2] = a[1].norm();
    row[jerk_m_s3] = j[0].norm(), row[jerkcmd_m_s3] = j[1].norm();
    row[fx_N] = c->force_N.x(), row[fy_N] = c->force_N.y();
    row[dx_um] = deflection.x() * 1e6, row[dy_um] = deflection.y() * 1e6;
    row[cx_um] = correction.x() * 1e6, row[cy_um] = correction.y() * 1e6;
    row[theta1_rad] = c->q_rad.x(), row[theta2_rad] = c->q_rad.y();
    row[omega1_rad_s] = c->qd_rad_s.x(), row[omega2_rad_s] = c->qd_rad_s.y();
    row[alpha1_rad_s2] = alpha.x(), row[alpha2_rad_s2] = alpha.y();
    row[power_pct] = c->laser_on ? c->power * 100.0 : 0.0;
    if (s.samples > 0 && prev.laser_on) s.laser_on_s += c->t_s - prev.t_s;
    if (c->laser_on) s.peak_power = std::max(s.peak_power, c->power);
    decimated.add(c->t_s, row);
    if ((s.samples == 0 || c->line != prev.line) && lines.size() < 1000000) lines.push_back({c->t_s, c->line});
    s.peak_speed_mm_s = std::max(s.peak_speed_mm_s, row[speed_mm_s]);
    s.peak_acceleration_m_s2 = std::max(s.peak_acceleration_m_s2, row[acc_m_s2]);
    s.peak_jerk_m_s3 = std::max(s.peak_jerk_m_s3, row[jerk_m_s3]);
    s.peak_force_N = std::max(s.peak_force_N, c->force_N.norm());
    s.peak_correction_um = std::max(s.peak_correction_um, correction.norm() * 1e6);
    v_prev = v, a_prev = a, omega_prev = c->qd_rad_s;
    prev = *c;
    ++s.samples;
  }
  if (s.samples < 2) throw Error(SourceLocation{joints}, "needs at least two samples to plot");
  s.duration_s = prev.t_s - t0;
  s.plotted = decimated.buckets().size();

  std::string data = fmt::format("# {}: {} samples, {} plotted (largest magnitude per bucket)\n# t_s", joints, s.samples,
                                 s.plotted);
  for (const char* n : kNames) data += std::string("\t") + n;
  data += "\n";
  for (const auto& b : decimated.buckets()) {
    data += fmt::format("{:.6f}", b.t_s);
    for (double x : b.v) data += fmt::format("\t{:.9g}", x);
    data += "\n";
  }
  const std::string file = name + ".tsv";
  core::write_file_atomically(dir / file, data);

  const kinematics::Robot* robot = options.robot;
  const std::string source =
      std::filesystem::path(joints).filename().string() +
      (robot ? fmt::format(" on {} (geometry {})", robot->name, robot->geometry_hash().substr(0, 12)) : std::string());
  const std::string head = fmt::format("set key outside right top\nset grid\nset lmargin 14\nset rmargin 30\n"
                                       "set xrange [{:.6f}:{:.6f}]\n",
                                       t0, prev.t_s);
  const std::string marks_labelled = markers(lines, options.max_line_markers, true);
  const std::string marks = markers(lines, options.max_line_markers, false);
  const std::string defl = file_has_deflection ? "predicted deflection Δ" : fmt::format("Δ = (p − p_cmd)/{:g}", options.gain);
  std::string motion = head + fmt::format("set multiplot layout 7,1 title {}\n",
                                          quote(fmt::format("{}: planned p and commanded p_cmd (G-code lines dotted)", source)));
  motion += panel("position (mm)", {series(x_mm, "x planned", 1, 1), series(xcmd_mm, "x commanded", 1, 2),
                                    series(y_mm, "y planned", 2, 1), series(ycmd_mm, "y commanded", 2, 2)},
                  marks_labelled, false);
  motion += panel("path speed (mm/s)", {series(speed_mm_s, "planned", 1, 1), series(speedcmd_mm_s, "commanded", 3, 2)},
                  marks, false);
  motion += panel("acceleration (m/s²)", {series(acc_m_s2, "planned", 1, 1), series(acccmd_m_s2, "commanded", 3, 2)},
                  marks, false);
  motion += panel("jerk (m/s³)", {series(jerk_m_s3, "planned", 1, 1), series(jerkcmd_m_s3, "commanded", 3, 2)}, marks,
                  false);
  motion += panel("D'Alembert force (N)", {series(fx_N, "F_x", 1, 1), series(fy_N, "F_y", 2, 1)}, marks, false);
  motion += panel("deflection, correction (µm)",
                  {series(dx_um, defl + " x", 1, 1), series(dy_um, defl + " y", 2, 1),
                   series(cx_um, "correction x", 1, 2), series(cy_um, "correction y", 2, 2)},
                  marks, false);
  motion += "set yrange [-5:105]\n" +
            panel("laser power (%)", {series(power_pct, "power (0 with the laser off)", 1, 1)}, marks, true) +
            "set autoscale y\n";
  motion += "unset multiplot\n";
  std::string joint = head + fmt::format("set multiplot layout 3,1 title {}\n",
                                         quote(fmt::format("{}: joint commands (G-code lines dotted)", source)));
  joint += panel("joint angle (rad)", {series(theta1_rad, "θ1", 1, 1), series(theta2_rad, "θ2", 2, 1)}, marks_labelled,
                 false);
  // The robot's limits as dashed lines: a joint's ±limit, in its colour.
  const auto limits = [robot](double kinematics::JointLimit::*field, const char* symbol) {
    std::vector<std::string> out;
    if (!robot) return out;
    for (int k = 0; k < 2; ++k) {
      const double limit = robot->joints[static_cast<std::size_t>(k)].*field;
      out.push_back(fmt::format("{:.9g} with lines lt {} dt 3 lw 1 title {}", limit, k + 1,
                                quote(fmt::format("±{}{} limit", symbol, k + 1))));
      out.push_back(fmt::format("{:.9g} with lines lt {} dt 3 lw 1 notitle", -limit, k + 1));
    }
    return out;
  };
  std::vector<std::string> omega{series(omega1_rad_s, "ω1", 1, 1), series(omega2_rad_s, "ω2", 2, 1)};
  std::vector<std::string> alphas{series(alpha1_rad_s2, "α1", 1, 1), series(alpha2_rad_s2, "α2", 2, 1)};
  for (auto& l : limits(&kinematics::JointLimit::max_velocity_rad_s, "ω")) omega.push_back(l);
  for (auto& l : limits(&kinematics::JointLimit::max_acceleration_rad_s2, "α")) alphas.push_back(l);
  joint += panel("joint velocity (rad/s)", omega, marks, false);
  joint += panel(file_has_alpha ? "joint acceleration (rad/s²)" : "joint acceleration, Δω/Δt (rad/s²)", alphas, marks,
                 true);
  joint += "unset multiplot\n";
  for (auto* text : {&motion, &joint}) *text = with_data(*text, file);
  render(dir, Figure{name + "_motion", motion, 1100, 1950, options.style});
  render(dir, Figure{name + "_joints", joint, 1100, 900, options.style});
  s.figures = {name + "_motion", name + "_joints"};
  return s;
}

}  // namespace stiffpath::report
