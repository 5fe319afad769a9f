// MEX command simulate: joint commands (run's struct or a joint file) through the digital twin, measured as
// `stiffpath simulate --json` measures them, stroke by stroke.
#include <fmt/format.h>

#include "mex_args.hpp"
#include "mex_commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/simulation/cg_lever.hpp"
#include "stiffpath/simulation/run_metrics.hpp"
#include "stiffpath/simulation/simulator.hpp"
#include "stiffpath/simulation/twin_models.hpp"

namespace stiffpath::mex {

namespace {

// The joint commands of run's struct J, row by row (t_s, q_rad, qd_rad_s, qdd_rad_s2 and laser required).
class StructJoints {
 public:
  explicit StructJoints(const mxArray* j) {
    if (mxGetNumberOfElements(j) != 1) throw UsageError("joints must be a 1×1 struct (from stiffpath('run', …))");
    t_ = get(j, "t_s", 1, true);
    n_ = t_->rows;
    q_ = get(j, "q_rad", 2, true);
    qd_ = get(j, "qd_rad_s", 2, true);
    qdd_ = get(j, "qdd_rad_s2", 2, true);
    target_ = get(j, "target_m", 2, false);
    command_ = get(j, "command_m", 2, false);
    force_ = get(j, "force_N", 2, false);
    power_ = get(j, "power", 1, false);
    line_ = get(j, "line", 1, false);
    laser_ = mxGetField(j, 0, "laser");
    if (laser_ == nullptr || mxGetNumberOfElements(laser_) != n_ || !(mxIsLogical(laser_) || mxIsDouble(laser_))) {
      throw UsageError("joints.laser must be logical or double with as many rows as joints.t_s");
    }
  }
  std::optional<compensation::JointCommand> next() {
    if (i_ == n_) return std::nullopt;
    const std::size_t i = i_++;
    const auto v = [&](const std::optional<Matrix>& m) { return m ? Vec2((*m)(i, 0), (*m)(i, 1)) : Vec2::Zero().eval(); };
    compensation::JointCommand c;
    c.t_s = (*t_)(i, 0);
    c.q_rad = v(q_);
    c.qd_rad_s = v(qd_);
    c.qdd_rad_s2 = v(qdd_);
    c.target_m = v(target_);
    c.command_m = command_ ? v(command_) : c.target_m;
    c.force_N = v(force_);
    c.laser_on = mxIsLogical(laser_) ? mxGetLogicals(laser_)[i] != 0 : mxGetPr(laser_)[i] != 0.0;
    c.power = power_ ? (*power_)(i, 0) : (c.laser_on ? 1.0 : 0.0);
    c.line = line_ ? static_cast<int>((*line_)(i, 0)) : static_cast<int>(i + 1);
    return c;
  }

 private:
  std::optional<Matrix> get(const mxArray* j, const char* name, std::size_t cols, bool required) {
    const mxArray* f = mxGetField(j, 0, name);
    if (f == nullptr) {
      if (required) throw UsageError(std::string("joints has no field ") + name + " (expected run's struct)");
      return std::nullopt;
    }
    const Matrix m = matrix_arg(f, std::string("joints.") + name, cols, cols);
    if (t_ && m.rows != n_) throw UsageError(std::string("joints.") + name + " must have as many rows as joints.t_s");
    return m;
  }
  std::optional<Matrix> t_, q_, qd_, qdd_, target_, command_, force_, power_, line_;
  const mxArray* laser_ = nullptr;
  std::size_t n_ = 0, i_ = 0;
};

// The meter, and the mark kept for the caller.
class Tap final : public simulation::StrokeObserver {
 public:
  Tap(simulation::RunMeter& meter) : meter_(meter) {}
  void begin_stroke(std::size_t index, double t_s) override {
    meter_.begin_stroke(index, t_s);
    starts.push_back(static_cast<double>(marked.size() + 1));
  }
  void command(const Vec2& target_m) override { meter_.command(target_m); }
  void mark(const Vec2& tip_m) override {
    meter_.mark(tip_m);
    marked.push_back(tip_m);
  }
  void end_stroke(double t_s) override { meter_.end_stroke(t_s); }
  std::vector<Vec2> marked;
  std::vector<double> starts;  // 1-based index into marked of each stroke's first point

 private:
  simulation::RunMeter& meter_;
};

mxArray* value_or_empty(double v, bool valid) { return valid ? mxCreateDoubleScalar(v) : mxCreateDoubleMatrix(0, 0, mxREAL); }

// The line metrics ([] when refused), AT_p and the corner metrics ([] without corners), as simulate --json's keys in SI.
void put_metrics(StructBuilder& b, const simulation::RunMetrics& m, bool path_accuracy) {
  const bool line = m.line_strokes > 0;
  b.add("length_m", value_or_empty(m.length_m, line));
  b.add("commanded_length_m", value_or_empty(m.commanded_length_m, line));
  b.add("length_error_m", value_or_empty(m.length_error_m, line));
  b.add("deviation_area_m2", value_or_empty(m.deviation_area_m2, line));
  b.add("max_deviation_m", value_or_empty(m.max_deviation_m, line));
  b.add("path_accuracy_m", value_or_empty(m.path_accuracy_m, path_accuracy));
  b.add("corners", static_cast<double>(m.corners));
  b.add("cornering_round_off_m", value_or_empty(m.cornering_round_off_m, m.corners > 0));
  b.add("cornering_overshoot_m", value_or_empty(m.cornering_overshoot_m, m.corners > 0));
}

mxArray* strokes_struct(const std::vector<simulation::StrokeMetrics>& strokes) {
  static const char* names[] = {"stroke", "start_s", "end_s", "marked_points", "sides", "length_m", "commanded_length_m",
                                "length_error_m", "deviation_area_m2", "max_deviation_m", "path_accuracy_m", "corners",
                                "cornering_round_off_m", "cornering_overshoot_m", "refusal"};
  constexpr int count = sizeof names / sizeof names[0];
  mxArray* s = mxCreateStructMatrix(1, strokes.size(), count, names);
  for (std::size_t i = 0; i < strokes.size(); ++i) {
    const auto& k = strokes[i];
    StructBuilder b;
    b.add("stroke", static_cast<double>(k.index + 1)).add("start_s", k.start_s).add("end_s", k.end_s);
    b.add("marked_points", static_cast<double>(k.marked_points)).add("sides", static_cast<double>(k.sides));
    put_metrics(b, k.metrics, k.path_accuracy);
    b.add("refusal", k.refusal);
    mxArray* one = b.build();
    for (int f = 0; f < count; ++f) {
      mxSetFieldByNumber(s, i, f, mxDuplicateArray(mxGetField(one, 0, names[f])));
    }
    mxDestroyArray(one);
  }
  return s;
}

}  // namespace

// m = stiffpath('simulate', robot, joints [, options]): joints is run's struct J or a joint file.
void simulate(int, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, 4, "m = stiffpath('simulate', robot, joints [, options])  % joints: run's struct or a joint file");
  const auto robot = robot_arg(prhs[1]);
  Options o(nrhs == 4 ? prhs[3] : nullptr);
  simulation::TrueComplianceOptions truth;
  simulation::SimulationOptions sim;
  truth.family = core::parse_enum<simulation::TrueFamily>(o.text("truth").value_or("structural"));
  truth.perturbation = o.number("perturbation", 0.0, 0.5).value_or(truth.perturbation);
  truth.seed = static_cast<std::uint64_t>(o.number("seed", 0.0, 4294967295.0).value_or(static_cast<double>(truth.seed)));
  const std::string servo = o.text("servo").value_or("loaded");
  if (servo != "loaded" && servo != "ideal") throw Error(fmt::format("options.servo: expected 'loaded' or 'ideal', got '{}'", servo));
  sim.plant.servo_feels_load = servo == "loaded";
  const std::string from = o.text("load_feedforward_from").value_or("reference");
  if (from != "reference" && from != "command") {
    throw Error(fmt::format("options.load_feedforward_from: expected 'reference' or 'command', got '{}'", from));
  }
  sim.plant.load_feedforward_from_command = from == "command";
  sim.plant.motor_inertia_kg_m2 = o.number("motor_inertia_kg_m2", 1e-5, 10.0, "kg·m²").value_or(sim.plant.motor_inertia_kg_m2);
  sim.plant.load_feedforward = o.number("load_feedforward", 0.0, 2.0).value_or(sim.plant.load_feedforward);
  sim.mass_scale = o.number("mass_scale", 0.1, 5.0).value_or(sim.mass_scale);
  if (const auto z = o.number("damping_ratio", 0.0, 2.0)) sim.plant.tip_damping_ratio = *z;
  sim.plant.servo_bandwidth_hz = o.number("servo_bandwidth_hz", 1.0, 2000.0, "Hz").value_or(sim.plant.servo_bandwidth_hz);
  sim.plant.step_rate_hz = o.number("step_rate_hz", 1000.0, 1e7, "Hz").value_or(sim.plant.step_rate_hz);
  sim.max_steps = static_cast<std::uint64_t>(o.number("max_steps", 1.0, 1e11).value_or(static_cast<double>(sim.max_steps)));
  const int sides = static_cast<int>(o.number("sides", 0.0, 12.0).value_or(0.0));
  evaluation::PathMetricsOptions metrics;
  metrics.corner_trim_m = o.number("corner_trim_m", 0.0, 1.0, "m").value_or(1e-3);
  const bool cg_lever = o.flag("cg_lever").value_or(true);
  const bool force_robot = o.flag("force_robot").value_or(false);
  o.finish();
  if (cg_lever) sim.cg_lever = simulation::make_cg_lever(robot);
  const auto plant_truth = simulation::make_true_compliance(robot, truth);
  simulation::RunMeter meter(sides, 100000, metrics);
  Tap tap(meter);
  simulation::SimulationResult result;
  std::string label;
  if (mxIsChar(prhs[2])) {
    label = text_arg(prhs[2], "joints");
    job::JointReader reader(label);
    if (!reader.mechanism().empty() && reader.mechanism() != robot.name && !force_robot) {
      throw Error(SourceLocation{label}, fmt::format("the joint file was written for robot '{}', not for '{}' (set "
                                                     "options.force_robot = true to simulate it anyway)",
                                                     reader.mechanism(), robot.name));
    }
    try {
      result = simulation::simulate([&] { return reader.next(); }, robot, plant_truth, sim,
                                    static_cast<simulation::StrokeObserver&>(tap));
    } catch (const simulation::RecordRefused& e) {
      throw Error(SourceLocation{label}, fmt::format("record {}: RANGE: {}", e.record() + 1, e.message()));
    }
  } else if (mxIsStruct(prhs[2])) {
    label = "joints";
    StructJoints joints(prhs[2]);
    try {
      result = simulation::simulate([&] { return joints.next(); }, robot, plant_truth, sim,
                                    static_cast<simulation::StrokeObserver&>(tap));
    } catch (const simulation::RecordRefused& e) {
      throw Error(fmt::format("joints row {}: {}", e.record() + 1, e.message()));
    }
  } else {
    throw UsageError("joints must be run's struct or a joint file name");
  }
  const simulation::RunMetrics m = meter.totals(result);
  StructBuilder b;
  b.add("joints", label).add("robot", robot.name).add("duration_s", result.duration_s);
  b.add("marked_points", static_cast<double>(tap.marked.size()));
  put_metrics(b, m, true);
  b.add("residual_vibration_m", m.residual_vibration_m).add("peak_deflection_m", m.peak_deflection_m);
  b.add("strokes", static_cast<double>(meter.stroke_count())).add("line_strokes", static_cast<double>(m.line_strokes));
  b.add("stroke_metrics", strokes_struct(meter.strokes()));
  b.add("marked_m", pairs(tap.marked)).add("stroke_starts", column(tap.starts));
  plhs[0] = b.build();
}

}  // namespace stiffpath::mex
