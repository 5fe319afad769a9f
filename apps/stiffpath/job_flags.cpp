// The main job's flags onto job::JobSpec: only names become enums here; the defaults are the library's.
#include "job_flags.hpp"

#include <fmt/format.h>

#include "bounded.hpp"
#include "job_budget.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::cli {

namespace {
template <core::NamedEnum E>
E parsed(const char* flag, const std::string& text) {
  try {
    return core::parse_enum<E>(text);
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", flag, e.message()));
  }
}
}  // namespace

void add_job_flags(CLI::App* cmd, JobFlags& a) {
  add_robot_flag(cmd, a.robot);
  add_model_flags(cmd, a.model);
  const job::JobSpec defaults;
  auto* thesis = cmd->add_flag("--thesis", a.thesis,
                               "The thesis's method: the bilinear model of the robot's table, quasi-static compensation, "
                               "no reference filter (for oc-gu: --model thesis-oc --compensation quasi-static --smooth-ms 0)");
  cmd->add_flag("--no-compensation", a.no_compensation,
                "Without compensation: the planned path converted to joints as it is (no reference filter unless one "
                "is named)");
  cmd->add_option("--gain", a.gain, fmt::format("Compensation gain k in p_cmd = p - k*delta (default {:g})", defaults.gain))
      ->check(within(0.0, 10.0, ""));
  cmd->add_option("--accel-source", a.accel_source,
                  "analytic (the profile's, default) or numeric (the thesis's second difference)")
      ->check(CLI::IsMember(core::enum_name_list<job::AccelerationSource>()));
  auto* method = cmd->add_option("--compensation", a.method,
                                 "dynamic (the tip's damped dynamics inverted, default) or quasi-static (the thesis's "
                                 "static deflection)")
                     ->check(CLI::IsMember(core::enum_name_list<compensation::Method>()));
  cmd->add_option("--damping-ratio", a.damping_ratio,
                  "Damping ratio of the tip's modes assumed by dynamic compensation and the shapers (default: the "
                  "robot file's tip_damping_ratio, 0.05 when it gives none)")
      ->check(within(0.0, 0.9, ""));
  auto* smooth = cmd->add_option("--smooth-ms", a.smooth_ms,
                                 "Two moving averages of half this width over the planned reference (ms, 0..1000; "
                                 "default 8 when compensating, 0 without): continuous jerk and snap")
                     ->check(within(0.0, 1000.0, "ms"));
  auto* shaper = cmd->add_option("--shaper", a.shaper, "Input shaper following the tip's frequency: none (default), zv or zvd")
                     ->check(CLI::IsMember({"none", "zv", "zvd"}));
  cmd->add_option("--outside", a.outside,
                  "A sample more than 1 mm outside the model's measured region: error (refuse), clamp or extrapolate "
                  "(default: the model's, error unless it was fitted otherwise)")
      ->check(CLI::IsMember(core::enum_name_list<compliance::OutsidePolicy>()));
  add_max_samples_flag(cmd, a.max_samples);
  cmd->add_option("--format", a.format, "Joint file format: csv or bin")
      ->check(CLI::IsMember(core::enum_name_list<job::OutputFormat>()))
      ->capture_default_str();
  add_motion_flags(cmd, a.motion);
  for (auto* other : {method, smooth, shaper}) thesis->excludes(other);
  thesis->excludes(cmd->get_option("--model"))->excludes(cmd->get_option("--method"));
}

job::JobSpec job_spec(const JobFlags& a) {
  const kinematics::Robot robot = load_robot_flag(a.robot);
  job::JobSpec spec = a.thesis ? job::thesis_job(robot) : job::default_job(robot);
  if (!a.thesis) spec.model.request = model_request(a.model);
  spec.model.request.force = a.model.force;
  spec.compensate = !a.no_compensation;
  if (a.gain) spec.gain = *a.gain;
  if (!a.accel_source.empty()) spec.acceleration = parsed<job::AccelerationSource>("--accel-source", a.accel_source);
  if (!a.method.empty()) spec.method = parsed<compensation::Method>("--compensation", a.method);
  if (a.damping_ratio) spec.damping_ratio = *a.damping_ratio;
  if (a.smooth_ms) spec.smooth_s = *a.smooth_ms * 1e-3;
  if (!a.shaper.empty()) spec.shaper = parsed<compensation::FilterKind>("--shaper", a.shaper);
  if (!a.outside.empty()) spec.outside = parsed<compliance::OutsidePolicy>("--outside", a.outside);
  spec.format = parsed<job::OutputFormat>("--format", a.format);
  spec.max_samples = a.max_samples;
  MotionFlags motion = a.motion;
  if (motion.jerk == "auto") {
    spec.jerk = job::JerkRule::tip_frequency;
    motion.jerk.clear();
  }
  spec.plan = plan_options(motion, robot);
  return spec;
}

}  // namespace stiffpath::cli
