// Drives the plant with a joint stream: Hermite-interpolated references, laser marks, then settling.
#include "stiffpath/simulation/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

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

RecordRefused::RecordRefused(std::size_t record, const std::string& message) : Error(message), record_(record) {}

namespace {

void check_finite(const Plant& plant, double t) {
  const auto& s = plant.state();
  if (!s.q_rad.allFinite() || !s.qd_rad_s.allFinite() || !s.tip_m.allFinite() || !s.tip_m_s.allFinite()) {
    throw Error(fmt::format("simulation diverged at t = {:.6f} s (step too large for the stiffness?)", t));
  }
}

// Why the robot cannot take the joint command q: a joint beyond its limits, arms that cannot close, a tip
// it cannot reach, or a working mode other than its own (the command went through a singularity).
// Empty when q is usable.
std::string joint_refusal(const kinematics::Robot& spec, const kinematics::FiveBar& robot, const Vec2& q) {
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& lim = spec.joints[i];
    const double v = q[static_cast<Eigen::Index>(i)];
    if (!(v >= lim.min_rad && v <= lim.max_rad)) {
      return fmt::format("{} = {:.3f} deg is beyond its {} limit of {:.3f} deg (range [{:.3f}, {:.3f}] deg)", lim.name,
                         v * 180 / std::numbers::pi, v > lim.max_rad ? "upper" : "lower",
                         (v > lim.max_rad ? lim.max_rad : lim.min_rad) * 180 / std::numbers::pi,
                         lim.min_rad * 180 / std::numbers::pi, lim.max_rad * 180 / std::numbers::pi);
    }
  }
  Vec2 p;
  try {
    p = robot.forward_checked(q);
  } catch (const Error& e) {
    return e.message();
  }
  const kinematics::InverseResult r = robot.solve_inverse(p);
  const auto where = [&] { return fmt::format("theta1 = {:.3f} deg, theta2 = {:.3f} deg put the tip at x = {:.3f} mm, y = {:.3f} mm",
                                              q[0] * 180 / std::numbers::pi, q[1] * 180 / std::numbers::pi, p.x() * 1e3,
                                              p.y() * 1e3); };
  if (r.status != kinematics::Reach::ok) return fmt::format("{}, which the robot cannot reach: {}", where(), robot.explain(p));
  const double turn = 2 * std::numbers::pi;
  const Vec2 d{std::remainder(r.q[0] - q[0], turn), std::remainder(r.q[1] - q[1], turn)};
  if (d.cwiseAbs().maxCoeff() > 1e-6) {
    return fmt::format("{} in another working mode than the robot's (its own joints there are {:.3f} and {:.3f} deg): the "
                       "command has passed through a singularity",
                       where(), r.q[0] * 180 / std::numbers::pi, r.q[1] * 180 / std::numbers::pi);
  }
  return {};
}

// Collects whole strokes for a StrokeSink.
class StrokeCollector final : public StrokeObserver {
 public:
  explicit StrokeCollector(const StrokeSink& sink) : sink_(sink) {}
  void begin_stroke(std::size_t index, double t_s) override {
    stroke_.index = index;
    stroke_.start_s = t_s;
    stroke_.marked.clear();
    stroke_.commanded.clear();
    stroke_.first_mark.clear();
  }
  void command(const Vec2& target_m) override {
    stroke_.commanded.push_back(target_m);
    stroke_.first_mark.push_back(stroke_.marked.size());
  }
  void mark(const Vec2& tip_m) override { stroke_.marked.push_back(tip_m); }
  void end_stroke(double t_s) override {
    stroke_.end_s = t_s;
    if (sink_) sink_(stroke_);
  }

 private:
  const StrokeSink& sink_;
  Stroke stroke_;
};

}  // namespace

SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot_spec,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options,
                          StrokeObserver& observer) {
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
  std::size_t record = 0;
  const auto check_record = [&](const compensation::JointCommand& c) {
    if (const std::string why = joint_refusal(robot_spec, robot, c.q_rad); !why.empty()) throw RecordRefused(record, why);
  };
  check_record(*first);
  // Jobs start at rest. A compensated jerk-limited start still commands the velocity step C·m·j of the
  // corrected target at t = 0; like every later jerk switch, the drive spreads it over one interval.
  first->qd_rad_s.setZero();
  first->qdd_rad_s2.setZero();
  plant.reset(first->q_rad);
  const double rate = options.plant.step_rate_hz;
  const auto mark_every = static_cast<std::uint64_t>(std::max(1.0, std::round(rate / options.mark_rate_hz)));
  const auto settle_steps = static_cast<std::uint64_t>(std::ceil(options.settle_s * rate));
  auto deflection = [&] { return (plant.state().tip_m - plant.base()).norm(); };
  compensation::JointCommand a = *first;
  const double t0 = a.t_s;
  bool open = false;        // a stroke is being marked
  bool a_commanded = false;  // `a` was handed to the observer
  const auto command = [&](const compensation::JointCommand& c) {
    if (!open) {
      open = true;
      observer.begin_stroke(out.strokes, c.t_s);
    }
    observer.command(c.target_m);
  };
  const auto end_stroke = [&](double t_s) {
    observer.end_stroke(t_s);
    open = false;
    ++out.strokes;
  };
  if (a.laser_on) {
    command(a);
    a_commanded = true;
    observer.mark(plant.state().tip_m);
  }
  for (auto b = source(); b; b = source()) {
    ++record;
    const double h = b->t_s - a.t_s;
    if (!(h > 0.0)) throw Error(fmt::format("simulation: time does not increase at t = {} s", b->t_s));
    check_record(*b);
    const double steps = std::ceil(h * rate - 1e-9);
    if (static_cast<double>(out.steps) + steps + static_cast<double>(settle_steps) > static_cast<double>(options.max_steps)) {
      throw RecordRefused(record, fmt::format("t = {:.6f} s takes the job beyond the simulation's work budget of {} "
                                              "integration steps ({:.1f} s of motion at {:g} Hz)",
                                              b->t_s, options.max_steps, static_cast<double>(options.max_steps) / rate, rate));
    }
    if (a.laser_on && !a_commanded) command(a);
    const int n = std::max(1, static_cast<int>(steps));
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
      if (a.laser_on && out.steps % mark_every == 0) observer.mark(plant.state().tip_m);
      start = r;
    }
    check_finite(plant, b->t_s);
    if (a.laser_on && !b->laser_on) {
      observer.command(b->target_m);
      end_stroke(b->t_s);
    }
    a = *b;
    a_commanded = false;
  }
  if (a.laser_on) {
    if (!a_commanded) command(a);
    end_stroke(a.t_s);
  }
  out.duration_s = a.t_s - t0;
  // Hold the last command and watch the tip ring down.
  const JointReference hold{a.q_rad, Vec2::Zero(), Vec2::Zero()};
  for (std::uint64_t i = 0; i < settle_steps; ++i) {
    plant.step(hold, 1.0 / rate);
    ++out.steps;
    out.residual_vibration_m = std::max(out.residual_vibration_m, deflection());
  }
  check_finite(plant, a.t_s + options.settle_s);
  return out;
}

SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options,
                          const StrokeSink& on_stroke) {
  StrokeCollector collector(on_stroke);
  return simulate(source, robot, std::move(truth), options, static_cast<StrokeObserver&>(collector));
}

SimulationResult simulate(const JointSource& source, const kinematics::Robot& robot,
                          std::shared_ptr<const compliance::Model> truth, const SimulationOptions& options) {
  std::vector<Vec2> marked, commanded;
  std::vector<std::size_t> first_mark;
  SimulationResult out = simulate(source, robot, std::move(truth), options, StrokeSink([&](const Stroke& s) {
    for (const auto k : s.first_mark) first_mark.push_back(marked.size() + k);
    marked.insert(marked.end(), s.marked.begin(), s.marked.end());
    commanded.insert(commanded.end(), s.commanded.begin(), s.commanded.end());
  }));
  out.marked = std::move(marked);
  out.commanded = std::move(commanded);
  out.first_mark = std::move(first_mark);
  return out;
}

}  // namespace stiffpath::simulation
