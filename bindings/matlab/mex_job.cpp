// MEX commands plan, run and compensate: the planner and the main job (job::JobSpec, the defaults every surface shares).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "mex_args.hpp"
#include "mex_commands.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"
#include "stiffpath/job/joint_record.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/prepared_job.hpp"
#include "stiffpath/motion/limits.hpp"
#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::mex {

namespace {

// The planner's options from an options struct, as the CLI's motion flags: accel (m/s² or text such as '5g'), jerk
// (m/s³; 'auto' only where `auto_jerk` is given: run), max_velocity_m_s, rate_hz, work_offset_m, start_m, blend
// ('on' | 'off'), blend_tolerance_m. G28 goes to the robot's home.
motion::PlanOptions plan_options(Options& o, const kinematics::Robot& robot, bool* auto_jerk) {
  motion::PlanOptions p;
  p.gcode.home_position_m = robot.home_m;
  auto& limits = p.limits;
  if (const mxArray* a = o.raw("accel")) {
    const double value = mxIsChar(a) ? units::parse_acceleration_m_s2(text_arg(a, o.name("accel")))
                                     : *o.number("accel", -1e300, 1e300);
    if (!(value >= motion::min_acceleration_limit_m_s2 && value <= motion::max_acceleration_limit_m_s2)) {
      throw Error(fmt::format("{}: expected {:g} … {:g} m/s², got {}", o.name("accel"), motion::min_acceleration_limit_m_s2,
                              motion::max_acceleration_limit_m_s2, value));
    }
    limits.max_acceleration_m_s2 = value;
  }
  limits.max_jerk_m_s3 = motion::default_jerk_m_s3(limits.max_acceleration_m_s2);
  if (const mxArray* j = o.raw("jerk"); j != nullptr && mxIsChar(j)) {
    const std::string text = text_arg(j, o.name("jerk"));
    if (text != "auto" || auto_jerk == nullptr) {
      throw Error(fmt::format("{}: expected a number (m/s³){}, got '{}'", o.name("jerk"),
                              auto_jerk != nullptr ? " or 'auto'" : " ('auto' is run's: it needs the tip's frequency)", text));
    }
    *auto_jerk = true;
  } else if (j != nullptr) {
    limits.max_jerk_m_s3 = *o.number("jerk", motion::min_jerk_limit_m_s3, motion::max_jerk_limit_m_s3, "m/s³");
  }
  limits.max_velocity_m_s = o.number("max_velocity_m_s", motion::min_velocity_limit_m_s, motion::max_velocity_limit_m_s, "m/s")
                                .value_or(limits.max_velocity_m_s);
  p.rate_hz = o.number("rate_hz", 1.0, 1e5, "Hz").value_or(p.rate_hz);
  if (const auto offset = o.point("work_offset_m")) p.gcode.work_offset_m = *offset;
  p.gcode.start_position_m = o.point("start_m");
  if (const auto blend = o.text("blend")) {
    if (*blend != "on" && *blend != "off") throw Error(fmt::format("{}: expected 'on' or 'off', got '{}'", o.name("blend"), *blend));
    p.gcode.initial_mode = *blend == "off" ? motion::JunctionMode::exact_stop : motion::JunctionMode::blend;
  }
  p.gcode.default_blend_tolerance_m =
      o.number("blend_tolerance_m", 0.0, motion::max_blend_tolerance_m, "m").value_or(p.gcode.default_blend_tolerance_m);
  return p;
}

mxArray* trajectory_struct(const std::vector<motion::TrajectorySample>& samples) {
  const std::size_t n = samples.size();
  std::vector<double> t(n), power(n), line(n);
  std::vector<Vec2> p(n), v(n), a(n), j(n);
  std::vector<bool> laser(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = samples[i];
    t[i] = s.t_s;
    p[i] = s.position_m;
    v[i] = s.velocity_m_s;
    a[i] = s.acceleration_m_s2;
    j[i] = s.jerk_m_s3;
    laser[i] = s.laser_on;
    power[i] = s.power;
    line[i] = s.line;
  }
  return StructBuilder()
      .add("t_s", column(t)).add("p_m", pairs(p)).add("v_m_s", pairs(v)).add("a_m_s2", pairs(a)).add("j_m_s3", pairs(j))
      .add("laser", logical_column(laser)).add("power", column(power)).add("line", column(line))
      .build();
}

// A job's sink that keeps every command.
class Commands final : public job::JointWriter {
 public:
  void write(const compensation::JointCommand& c) override { all.push_back(c); }
  void finish() override {}
  std::vector<compensation::JointCommand> all;
};

// run's struct J: the joint file's fields (job::kJointFields), one struct field per member in the table's order (N×2
// for a pair, logical for the laser, N×1 otherwise), then the deflection and the grid flag, which files do not hold.
mxArray* joints_struct(const std::vector<compensation::JointCommand>& commands) {
  const std::size_t n = commands.size();
  const auto& fields = job::kJointFields;
  StructBuilder b;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    const job::JointField& f = fields[k];
    if (f.component != 0) continue;  // a pair's second column is filled with its first
    const std::size_t cols = k + 1 < fields.size() && fields[k + 1].member == f.member ? 2 : 1;
    if (f.csv_text == job::CsvText::flag) {
      std::vector<bool> flags(n);
      for (std::size_t i = 0; i < n; ++i) flags[i] = job::value_of(commands[i], f) != 0.0;
      b.add(std::string(job::member_name(f.member)), logical_column(flags));
      continue;
    }
    mxArray* a = mxCreateDoubleMatrix(n, cols, mxREAL);
    double* out = mxGetPr(a);
    for (std::size_t c = 0; c < cols; ++c) {
      for (std::size_t i = 0; i < n; ++i) out[c * n + i] = job::value_of(commands[i], fields[k + c]);
    }
    b.add(std::string(job::member_name(f.member)), a);
  }
  std::vector<Vec2> deflection(n);
  std::vector<bool> outside(n);
  for (std::size_t i = 0; i < n; ++i) {
    deflection[i] = commands[i].deflection_m;
    outside[i] = commands[i].outside_grid;
  }
  return b.add("deflection_m", pairs(deflection)).add("outside_grid", logical_column(outside)).build();
}

// What `stiffpath run --json` reports, in SI.
mxArray* summary_struct(const job::PreparedJob& job, const job::JobSummary& s) {
  const job::JobSpec& spec = job.spec;
  StructBuilder b;
  b.add("job", job.program.label()).add("robot", spec.robot.name).add("model", job.model_label);
  b.add_bool("compensation", spec.compensate);
  b.add("method", spec.compensate ? std::string(core::enum_name(spec.method)) : std::string("none"));
  b.add("gain", spec.compensate ? spec.gain : 0.0).add("acceleration_source", std::string(core::enum_name(spec.acceleration)));
  b.add("damping_ratio", *spec.damping_ratio).add("smooth_s", *spec.smooth_s);
  b.add("shaper", std::string(core::enum_name(spec.shaper))).add("filters", job.filters_text());
  b.add("laser_on_delay_s", *spec.laser_on_delay_s).add("laser_off_delay_s", *spec.laser_off_delay_s);
  b.add("jerk_m_s3", spec.plan.limits.max_jerk_m_s3);
  b.add("lowest_frequency_hz", job.lowest_frequency_hz > 0.0 ? mxCreateDoubleScalar(job.lowest_frequency_hz)
                                                              : mxCreateDoubleMatrix(0, 0, mxREAL));
  b.add("duration_s", s.duration_s).add("samples", static_cast<double>(s.samples)).add("rate_hz", spec.plan.rate_hz);
  b.add("peak_deflection_m", s.peak_deflection_m).add("peak_correction_m", s.peak_correction_m);
  b.add("peak_force_N", s.peak_force_N).add("peak_joint_velocity_rad_s", s.peak_joint_velocity_rad_s);
  b.add("peak_joint_acceleration_rad_s2", s.peak_joint_acceleration_rad_s2);
  b.add("samples_outside_grid", static_cast<double>(s.samples_outside_grid));
  return b.build();
}

// The compensation options of run and compensate onto a JobSpec (the robot and model already chosen).
void compensation_options(Options& o, job::JobSpec& spec, bool thesis) {
  if (const auto c = o.flag("compensate")) spec.compensate = *c;
  if (const auto m = o.text("method")) spec.method = core::parse_enum<compensation::Method>(*m);
  if (const auto g = o.number("gain", 0.0, 10.0)) spec.gain = *g;
  if (const auto z = o.number("damping_ratio", 0.0, 0.9)) spec.damping_ratio = *z;
  if (const auto w = o.number("smooth_s", 0.0, 1.0, "s")) spec.smooth_s = *w;
  if (const auto s = o.text("shaper")) spec.shaper = core::parse_enum<compensation::FilterKind>(*s);
  if (const auto out = o.text("outside")) spec.outside = core::parse_enum<compliance::OutsidePolicy>(*out);
  if (const auto a = o.text("acceleration")) spec.acceleration = core::parse_enum<job::AccelerationSource>(*a);
  if (const auto d = o.number("laser_on_delay_s", -0.05, 0.05, "s")) spec.laser_on_delay_s = *d;
  if (const auto d = o.number("laser_off_delay_s", -0.05, 0.05, "s")) spec.laser_off_delay_s = *d;
  if (thesis && (o.has("method") || o.has("smooth_s") || o.has("shaper") || o.has("model"))) {
    throw UsageError("options.thesis names its own model, method and filters: give none of model, method, smooth_s, shaper");
  }
}

// The JobSpec of run/compensate from the robot and the options (thesis, model, force_model, then the rest).
job::JobSpec job_spec(const kinematics::Robot& robot, Options& o, const std::string* model) {
  const bool thesis = o.flag("thesis").value_or(false);
  job::JobSpec spec = thesis ? job::thesis_job(robot) : job::default_job(robot);
  const auto named = model != nullptr ? std::optional<std::string>(*model) : o.text("model");
  if (named && !(thesis && named->empty())) {
    if (thesis) throw UsageError("options.thesis names its own model: give none");
    spec.model.request.model = *named;
  }
  spec.model.request.force = o.flag("force_model").value_or(false);
  spec.model.request.how_to_force = "set options.force_model = true";
  compensation_options(o, spec, thesis);
  return spec;
}

void return_job(int nlhs, mxArray* plhs[], const job::PreparedJob& prepared) {
  Commands commands;
  const job::JobSummary summary = job::run(prepared, &commands);
  plhs[0] = joints_struct(commands.all);
  if (nlhs > 1) plhs[1] = summary_struct(prepared, summary);
}

// The planned samples given to compensate: plan's struct, or the N×7…10 matrix [t x y vx vy ax ay (jx jy laser)].
std::vector<motion::TrajectorySample> samples_arg(const mxArray* a) {
  std::vector<motion::TrajectorySample> out;
  if (mxIsStruct(a)) {
    if (mxGetNumberOfElements(a) != 1) throw UsageError("T must be a 1×1 struct (from stiffpath('plan', …))");
    const auto field = [&](const char* name, std::size_t cols, bool required) -> std::optional<Matrix> {
      const mxArray* f = mxGetField(a, 0, name);
      if (f == nullptr) {
        if (required) throw UsageError(std::string("T has no field ") + name + " (expected plan's struct)");
        return std::nullopt;
      }
      return matrix_arg(f, std::string("T.") + name, cols, cols);
    };
    const Matrix t = *field("t_s", 1, true), p = *field("p_m", 2, true), v = *field("v_m_s", 2, true),
                 acc = *field("a_m_s2", 2, true);
    const auto j = field("j_m_s3", 2, false), power = field("power", 1, false), line = field("line", 1, false);
    const mxArray* laser = mxGetField(a, 0, "laser");
    const std::size_t n = t.rows;
    for (const auto* m : {&p, &v, &acc}) {
      if (m->rows != n) throw UsageError("T's fields must have as many rows as T.t_s");
    }
    for (const auto& m : {j, power, line}) {
      if (m && m->rows != n) throw UsageError("T's fields must have as many rows as T.t_s");
    }
    if (laser != nullptr && (mxGetNumberOfElements(laser) != n || !(mxIsLogical(laser) || mxIsDouble(laser)))) {
      throw UsageError("T.laser must be logical or double with as many rows as T.t_s");
    }
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      auto& s = out[i];
      s.t_s = t(i, 0);
      s.position_m = Vec2(p(i, 0), p(i, 1));
      s.velocity_m_s = Vec2(v(i, 0), v(i, 1));
      s.acceleration_m_s2 = Vec2(acc(i, 0), acc(i, 1));
      if (j) s.jerk_m_s3 = Vec2((*j)(i, 0), (*j)(i, 1));
      s.laser_on = laser != nullptr && (mxIsLogical(laser) ? mxGetLogicals(laser)[i] != 0 : mxGetPr(laser)[i] != 0.0);
      s.power = power ? (*power)(i, 0) : (s.laser_on ? 1.0 : 0.0);
      s.line = line ? static_cast<int>((*line)(i, 0)) : static_cast<int>(i + 1);
    }
    return out;
  }
  const Matrix m = matrix_arg(a, "T", 7, 10);
  out.resize(m.rows);
  for (std::size_t i = 0; i < m.rows; ++i) {
    const auto col = [&](std::size_t c) { return c < m.cols ? m(i, c) : 0.0; };
    auto& s = out[i];
    s.t_s = col(0);
    s.position_m = Vec2(col(1), col(2));
    s.velocity_m_s = Vec2(col(3), col(4));
    s.acceleration_m_s2 = Vec2(col(5), col(6));
    s.jerk_m_s3 = Vec2(col(7), col(8));
    s.laser_on = col(9) != 0.0;
    s.power = s.laser_on ? 1.0 : 0.0;
    s.line = static_cast<int>(i + 1);
  }
  return out;
}

}  // namespace

// [T, summary] = stiffpath('plan', gcode_file [, options]).
void plan(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 2, 3, "[T, summary] = stiffpath('plan', gcode_file [, options])  % options: robot, accel, jerk, max_velocity_m_s, "
                   "rate_hz, work_offset_m, start_m, blend, blend_tolerance_m, max_samples");
  const std::string file = text_arg(prhs[1], "gcode_file");
  Options o(nrhs == 3 ? prhs[2] : nullptr);
  const auto robot = kinematics::load_robot(o.text("robot").value_or("oc-gu"));
  const motion::PlanOptions options = plan_options(o, robot, nullptr);
  const double max_samples = o.number("max_samples", 1.0, static_cast<double>(job::kMaxJobSamples)).value_or(job::kDefaultMaxSamples);
  o.finish();
  motion::TrajectoryStream stream(file, options);
  const auto five_bar = robot.five_bar();
  std::vector<motion::TrajectorySample> samples;
  double peak_v = 0.0, peak_a = 0.0, peak_j = 0.0, laser_on_s = 0.0;
  while (auto s = stream.next()) {
    if (static_cast<double>(samples.size()) >= max_samples) {
      throw Error(SourceLocation{file, s->line},
                  fmt::format("the program needs more than options.max_samples = {:g} samples at {:g} Hz", max_samples, options.rate_hz));
    }
    const auto r = five_bar.solve_inverse(s->position_m);
    if (r.status != kinematics::Reach::ok || !robot.within_limits(r.q)) {  // as `stiffpath plan`
      throw Error(SourceLocation{file, s->line},
                  fmt::format("t = {:.4f} s: point (x = {:.4f} mm, y = {:.4f} mm) is outside robot {}'s workspace: {}", s->t_s,
                              s->position_m.x() * 1e3, s->position_m.y() * 1e3, robot.name, robot.refusal(s->position_m)));
    }
    peak_v = std::max(peak_v, s->velocity_m_s.norm());
    peak_a = std::max(peak_a, s->acceleration_m_s2.norm());
    peak_j = std::max(peak_j, s->jerk_m_s3.norm());
    if (s->laser_on) laser_on_s += 1.0 / options.rate_hz;
    samples.push_back(*s);
  }
  plhs[0] = trajectory_struct(samples);
  if (nlhs > 1) {
    plhs[1] = StructBuilder()
                  .add("job", file).add("robot", robot.name)
                  .add("duration_s", samples.empty() ? 0.0 : samples.back().t_s)
                  .add("samples", static_cast<double>(samples.size())).add("rate_hz", options.rate_hz)
                  .add("peak_velocity_m_s", peak_v).add("peak_acceleration_m_s2", peak_a).add("peak_jerk_m_s3", peak_j)
                  .add("max_velocity_m_s", options.limits.max_velocity_m_s)
                  .add("max_acceleration_m_s2", options.limits.max_acceleration_m_s2)
                  .add("max_jerk_m_s3", options.limits.max_jerk_m_s3)
                  .build();
  }
}

// [J, summary] = stiffpath('run', gcode_file, robot [, options]): the main job exactly as `stiffpath run` makes it.
void run(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 3, 4, "[J, summary] = stiffpath('run', gcode_file, robot [, options])  % stiffpath('help', 'run') lists the options");
  const std::string file = text_arg(prhs[1], "gcode_file");
  const auto robot = robot_arg(prhs[2]);
  Options o(nrhs == 4 ? prhs[3] : nullptr);
  job::JobSpec spec = job_spec(robot, o, nullptr);
  bool auto_jerk = false;
  spec.plan = plan_options(o, robot, &auto_jerk);
  if (auto_jerk) spec.jerk = job::JerkRule::tip_frequency;
  if (const auto m = o.number("max_samples", 1.0, static_cast<double>(job::kMaxJobSamples))) spec.max_samples = static_cast<std::uint64_t>(*m);
  o.finish();
  const job::PreparedJob prepared = job::prepare(std::move(spec), job::Program::file(file));
  job::check_output(prepared, "-");  // kept in memory: the cap of a written job holds
  return_job(nlhs, plhs, prepared);
}

// [J, summary] = stiffpath('compensate', robot, model, T [, options]): the main job on planned samples T.
void compensate(int nlhs, mxArray* plhs[], int nrhs, const mxArray* prhs[]) {
  need(nrhs, 4, 5, "[J, summary] = stiffpath('compensate', robot, model, T [, options])  % model '' = the robot's own");
  const auto robot = robot_arg(prhs[1]);
  const std::string model = text_arg(prhs[2], "model");
  job::JobSpec spec = job::default_job(robot);
  if (nrhs == 5 && mxIsDouble(prhs[4]) && mxGetNumberOfElements(prhs[4]) == 1) {  // a plain number: the gain
    Options none(nullptr);
    spec = job_spec(robot, none, &model);
    spec.gain = mxGetScalar(prhs[4]);
  } else {
    Options o(nrhs == 5 ? prhs[4] : nullptr);
    spec = job_spec(robot, o, &model);
    if (o.has("rate_hz")) spec.plan.rate_hz = *o.number("rate_hz", 1.0, 1e5, "Hz");
    o.finish();
  }
  auto samples = samples_arg(prhs[3]);
  const job::PreparedJob prepared = job::prepare(std::move(spec), job::Program::samples(std::move(samples), "T"));
  return_job(nlhs, plhs, prepared);
}

}  // namespace stiffpath::mex
