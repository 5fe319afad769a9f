// Drives the plant with a joint stream: Hermite-interpolated references, laser marks, then settling.
#include "stiffpath/simulation/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "stiffpath/core/error.hpp"

namespace stiffpath::simulation {

JointReference interpolate(const compensation::JointCommand& a, const compensation::JointCommand& b, double s) noexcept {
  const double h = b.t_s - a.t_s;
  const double s2 = s * s, s3 = s2 * s;
  // Hermite basis and its derivatives with respect to s.
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1, d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
  const double e00 = 12 * s - 6, e10 = 6 * s - 4, e01 = -12 * s + 6, e11 = 6 * s - 2;
  const Vec2 ma = h * a.qd_rad_s, mb = h * b.qd_rad_s;
  JointReference r;
  r.q_rad = h00 * a.q_rad + h10 * ma + h01 * b.q_rad + h11 * mb;
  r.qd_rad_s = (d00 * a.q_rad + d10 * ma + d01 * b.q_rad + d11 * mb) / h;
  r.qdd_rad_s2 = (e00 * a.q_rad + e10 * ma + e01 * b.q_rad + e11 * mb) / (h * h);
  r.load_force_N = -((1.0 - s) * a.force_N + s * b.force_N);
  return r;
}

namespace {

void check_finite(const Plant& plant, double t) {
  const auto& s = plant.state();
  if (!s.q_rad.allFinite() || !s.qd_rad_s.allFinite() || !s.tip_m.allFinite() || !s.tip_m_s.allFinite()) {
    throw Error(fmt::format("simulation diverged at t = {:.6f} s (step too large for the stiffness?)", t));
  }
}

}  // namespace

SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot_spec,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options,
                          const StrokeSink& on_stroke) {
  if (!(options.mass_scale > 0.0 && options.mass_scale < 10.0)) {
    throw Error(fmt::format("simulation: mass_scale {} outside (0, 10)", options.mass_scale));
  }
  if (!(options.settle_s >= 0.0) || !(options.mark_rate_hz > 0.0)) {
    throw Error(fmt::format("simulation: settle_s {} must be ≥ 0 and mark_rate_hz {} > 0", options.settle_s,
                            options.mark_rate_hz));
  }
  const kinematics::FiveBar robot = robot_spec.five_bar();
  PlantOptions plant_options = options.plant;
  if (plant_options.controller_mass_kg == 0.0) plant_options.controller_mass_kg = robot_spec.moving_mass_kg;
  if (!plant_options.tip_damping_ratio) plant_options.tip_damping_ratio = robot_spec.tip_damping_ratio;
  Plant plant(robot, std::move(truth), robot_spec.moving_mass_kg * options.mass_scale, plant_options, options.cg_lever);
  SimulationResult out;
  auto first = source();
  if (!first) throw Error("simulation: the joint trajectory is empty");
  // Jobs start at rest. A compensated jerk-limited start still commands the velocity step C·m·j of the
  // corrected target at t = 0; like every later jerk switch, the drive spreads it over one interval.
  first->qd_rad_s.setZero();
  first->qdd_rad_s2.setZero();
  plant.reset(first->q_rad);
  const double rate = options.plant.step_rate_hz;
  const auto mark_every = static_cast<std::uint64_t>(std::max(1.0, std::round(rate / options.mark_rate_hz)));
  auto deflection = [&] { return (plant.state().tip_m - plant.base()).norm(); };
  compensation::JointCommand a = *first;
  const double t0 = a.t_s;
  Stroke stroke;  // the stroke being marked; its buffers are reused from one stroke to the next
  const auto end_stroke = [&](const Vec2& last_target, double t_s) {
    stroke.commanded.push_back(last_target);
    stroke.end_s = t_s;
    if (on_stroke) on_stroke(stroke);
    ++out.strokes;
    stroke.index = out.strokes;
    stroke.marked.clear();
    stroke.commanded.clear();
  };
  if (a.laser_on) {
    stroke.start_s = a.t_s;
    stroke.marked.push_back(plant.state().tip_m);
  }
  for (auto b = source(); b; b = source()) {
    const double h = b->t_s - a.t_s;
    if (!(h > 0.0)) throw Error(fmt::format("simulation: time does not increase at t = {} s", b->t_s));
    if (a.laser_on) {
      if (stroke.commanded.empty()) stroke.start_s = a.t_s;
      stroke.commanded.push_back(a.target_m);
    }
    const int n = std::max(1, static_cast<int>(std::ceil(h * rate - 1e-9)));
    JointReference start = interpolate(a, *b, 0.0);
    for (int i = 1; i <= n; ++i) {
      // The servo law sees the reference at the start of the step, where its state is (a symplectic
      // Euler step then follows a ramp exactly); the error is checked against the end of the step,
      // whose reference starts the next step.
      plant.step(start, h / n);
      const JointReference r = interpolate(a, *b, static_cast<double>(i) / n);
      ++out.steps;
      out.peak_deflection_m = std::max(out.peak_deflection_m, deflection());
      out.peak_tracking_error_m =
          std::max(out.peak_tracking_error_m, (plant.base() - robot.forward(r.q_rad)).norm());
      if (a.laser_on && out.steps % mark_every == 0) stroke.marked.push_back(plant.state().tip_m);
      start = r;
    }
    check_finite(plant, b->t_s);
    if (a.laser_on && !b->laser_on) end_stroke(b->target_m, b->t_s);
    a = *b;
  }
  if (a.laser_on) {
    if (stroke.commanded.empty()) stroke.start_s = a.t_s;
    end_stroke(a.target_m, a.t_s);
  }
  out.duration_s = a.t_s - t0;
  // Hold the last command and watch the tip ring down.
  const JointReference hold{a.q_rad, Vec2::Zero(), Vec2::Zero()};
  const auto settle_steps = static_cast<std::uint64_t>(std::ceil(options.settle_s * rate));
  for (std::uint64_t i = 0; i < settle_steps; ++i) {
    plant.step(hold, 1.0 / rate);
    ++out.steps;
    out.residual_vibration_m = std::max(out.residual_vibration_m, deflection());
  }
  check_finite(plant, a.t_s + options.settle_s);
  return out;
}

SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options) {
  std::vector<Vec2> marked, commanded;
  SimulationResult out = simulate(source, robot, std::move(truth), options, [&](const Stroke& s) {
    marked.insert(marked.end(), s.marked.begin(), s.marked.end());
    commanded.insert(commanded.end(), s.commanded.begin(), s.commanded.end());
  });
  out.marked = std::move(marked);
  out.commanded = std::move(commanded);
  return out;
}

}  // namespace stiffpath::simulation
