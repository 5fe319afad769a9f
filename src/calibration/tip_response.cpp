// predict_marks: the compliant tip driven by the commanded base motion, recorded while the laser lights it.
#include "stiffpath/calibration/tip_response.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::calibration {

namespace {

// The base point's state at one command: position, velocity, acceleration, and the tip's matrices there.
struct BaseSample {
  double t_s = 0.0;
  Vec2 p, v, a;
  Mat2 Q;        // m·S·C·S (m per m/s²)
  Mat2 A;        // s_f·Q^{-1/2} (rad/s)
  bool laser = false;
};

// A laser pulse: from the command that switches it on to the one that switches it off (or the last).
struct Pulse {
  std::size_t rise = 0;
  double on_s = 0.0, off_s = 0.0;  // when the light is on, delays included
};

Vec2 hermite(const BaseSample& a, const BaseSample& b, double s) {
  const double h = b.t_s - a.t_s;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * a.p + (s3 - 2 * s2 + s) * h * a.v + (-2 * s3 + 3 * s2) * b.p + (s3 - s2) * h * b.v;
}

}  // namespace

std::vector<PredictedMark> predict_marks(const std::vector<compensation::JointCommand>& commands,
                                         const kinematics::Robot& robot, const compliance::Model& model,
                                         const TipParameters& x, const ResponseOptions& options) {
  if (commands.size() < 2) throw Error("calibration: the joint commands hold fewer than two samples");
  if (options.steps_per_command < 1 || options.steps_per_command > 1000) throw Error("calibration: 1 … 1000 steps per command");
  const kinematics::FiveBar five_bar = robot.five_bar();
  const double m = robot.moving_mass_kg;
  std::vector<BaseSample> base(commands.size());
  for (std::size_t k = 0; k < commands.size(); ++k) {
    const auto& c = commands[k];
    BaseSample& b = base[k];
    b.t_s = c.t_s;
    b.p = five_bar.forward(c.q_rad);
    b.v = five_bar.velocity(c.q_rad, c.qd_rad_s);
    b.a = five_bar.acceleration(c.q_rad, c.qd_rad_s, c.qdd_rad_s2);
    const Mat2 S = x.correction.matrix(model.bounds().clamp(b.p));
    b.Q = m * (S * model.compliance(b.p) * S);
    const Mat2 root = compensation::matrix_sqrt(b.Q);
    b.A = root.determinant() > 0.0 ? Mat2(x.frequency_scale * root.inverse()) : Mat2(Mat2::Zero());
    b.laser = c.laser_on;
  }
  // The pulses, with the light's own on and off times.
  std::vector<Pulse> pulses;
  for (std::size_t k = 0; k < base.size(); ++k) {
    if (!base[k].laser || (k > 0 && base[k - 1].laser)) continue;
    std::size_t fall = k;
    while (fall < base.size() && base[fall].laser) ++fall;
    const double off = fall < base.size() ? base[fall].t_s : base.back().t_s;
    pulses.push_back({k, base[k].t_s + x.laser_on_delay_s, off + x.laser_off_delay_s});
  }
  std::vector<PredictedMark> marks(pulses.size());
  for (std::size_t i = 0; i < pulses.size(); ++i) {
    marks[i].first_command = pulses[i].rise;
    marks[i].commanded_start_m = commands[pulses[i].rise].target_m;
  }

  // The tip from rest, undeflected; each command interval in equal steps, the matrices of its first command.
  Vec2 e = Vec2::Zero(), e_dot = Vec2::Zero();
  Vec2 last_tool = base.front().p;
  double last_t = base.front().t_s;
  const double zeta2 = 2.0 * x.damping_ratio;
  std::size_t first_open = 0;  // pulses before it are over
  const auto record = [&](double t, const Vec2& tool) {
    // Points of every pulse lit somewhere in (last_t, t]: the ends interpolated to the light's exact times.
    for (std::size_t i = first_open; i < pulses.size() && pulses[i].on_s <= t; ++i) {
      const Pulse& p = pulses[i];
      if (p.off_s < last_t) {
        if (i == first_open) ++first_open;
        continue;
      }
      const auto at = [&](double when) {
        const double f = t > last_t ? std::clamp((when - last_t) / (t - last_t), 0.0, 1.0) : 1.0;
        return Vec2(last_tool + f * (tool - last_tool));
      };
      auto& points = marks[i].points_m;
      if (p.on_s > last_t) points.push_back(at(p.on_s));
      if (p.off_s <= t) {
        points.push_back(at(p.off_s));
      } else {
        points.push_back(tool);
      }
    }
    last_t = t;
    last_tool = tool;
  };
  for (std::size_t k = 0; k + 1 < base.size(); ++k) {
    const BaseSample& a = base[k];
    const BaseSample& b = base[k + 1];
    const double h = b.t_s - a.t_s;
    if (!(h > 0.0)) throw Error("calibration: the joint commands' times must increase");
    const int n = options.steps_per_command;
    const double dt = h / n;
    const Mat2 A2 = a.A * a.A;
    for (int j = 1; j <= n; ++j) {
      const double s = static_cast<double>(j) / n;
      const Vec2 acc = a.a + s * (b.a - a.a);
      e_dot += dt * (-zeta2 * (a.A * e_dot) - A2 * (e + a.Q * acc));
      e += dt * e_dot;
      record(a.t_s + s * h, hermite(a, b, s) + e);
    }
  }
  if (!e.allFinite()) throw Error("calibration: the tip's predicted motion is not finite (parameters out of range)");
  return marks;
}

}  // namespace stiffpath::calibration
