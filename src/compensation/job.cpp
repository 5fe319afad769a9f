// run_job: the streaming offline pipeline with its summary and located errors.
#include "stiffpath/compensation/job.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "stiffpath/compensation/numeric_acceleration.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::compensation {

AccelerationSource parse_acceleration_source(const std::string& text) {
  if (text == "analytic") return AccelerationSource::analytic;
  if (text == "numeric") return AccelerationSource::numeric;
  throw Error("acceleration source '" + text + "' is not one of analytic, numeric");
}

TaskSample to_task_sample(const motion::TrajectorySample& s) noexcept {
  TaskSample t;
  t.t_s = s.t_s;
  t.position_m = s.position_m;
  t.velocity_m_s = s.velocity_m_s;
  t.acceleration_m_s2 = s.acceleration_m_s2;
  t.jerk_m_s3 = s.jerk_m_s3;
  t.laser_on = s.laser_on;
  t.line = s.line;
  return t;
}

namespace {
// The refusal of one sample as an error message naming the quantity, its value and its limit.
[[noreturn]] void refuse(const JointCommand& c, const Compensator& comp, const std::string& job) {
  const SourceLocation where{job, c.line};
  const std::string when = fmt::format("t = {:.4f} s", c.t_s);
  const auto& spec = comp.mechanism();
  const auto joint = [&]() -> const kinematics::JointLimit& { return spec.joints[static_cast<std::size_t>(std::max(c.joint, 0))]; };
  const int j = std::max(c.joint, 0);
  switch (c.status) {
    case Status::unreachable:
      throw Error(where, fmt::format("{}: corrected target (x = {:.4f} mm, y = {:.4f} mm) is not reachable: {}", when,
                                     units::m_to_mm(c.command_m.x()), units::m_to_mm(c.command_m.y()),
                                     kinematics::describe(comp.mechanism().five_bar().check_reach(c.command_m))));
    case Status::joint_position:
      throw Error(where, fmt::format("{}: joint {} position {:.3f} deg outside [{:.1f}, {:.1f}] deg", when, joint().name,
                                     units::rad_to_deg(c.q_rad[j]), units::rad_to_deg(joint().min_rad),
                                     units::rad_to_deg(joint().max_rad)));
    case Status::joint_velocity:
      throw Error(where, fmt::format("{}: joint {} velocity {:.2f} rad/s exceeds the limit {:.2f} rad/s", when,
                                     joint().name, c.qd_rad_s[j], joint().max_velocity_rad_s));
    case Status::joint_acceleration:
      throw Error(where, fmt::format("{}: joint {} acceleration {:.1f} rad/s^2 exceeds the limit {:.1f} rad/s^2", when,
                                     joint().name, c.qdd_rad_s2[j], joint().max_acceleration_rad_s2));
    case Status::outside_grid:
      throw Error(where, fmt::format("{}: (x = {:.4f} mm, y = {:.4f} mm) is outside the compliance model's grid and its "
                                     "policy is 'error'",
                                     when, units::m_to_mm(c.target_m.x()), units::m_to_mm(c.target_m.y())));
    case Status::not_finite: throw Error(where, when + ": the planned sample is not finite");
    case Status::ok: break;
  }
  throw Error(where, when + ": " + describe(c.status));
}
}  // namespace

JobSummary run_job(motion::SampleSource& source, const Compensator& compensator, JointWriter* writer,
                   const std::string& job_label, double rate_hz, AccelerationSource acceleration,
                   const Progress& progress) {
  JobSummary summary;
  const auto consume = [&](const TaskSample& sample) {
    const JointCommand c = compensator.step(sample);
    if (c.status != Status::ok) refuse(c, compensator, job_label);
    summary.duration_s = c.t_s;
    summary.peak_deflection_m = std::max(summary.peak_deflection_m, c.deflection_m.norm());
    summary.peak_correction_m = std::max(summary.peak_correction_m, (c.command_m - c.target_m).norm());
    summary.peak_force_N = std::max(summary.peak_force_N, c.force_N.norm());
    summary.peak_joint_velocity_rad_s = std::max(summary.peak_joint_velocity_rad_s, c.qd_rad_s.cwiseAbs().maxCoeff());
    summary.peak_joint_acceleration_rad_s2 =
        std::max(summary.peak_joint_acceleration_rad_s2, c.qdd_rad_s2.cwiseAbs().maxCoeff());
    summary.samples_outside_grid += c.outside_grid ? 1 : 0;
    if (writer) writer->write(c);
    if ((++summary.samples & 0xffff) == 0 && progress) progress(summary.samples, c.line);
  };
  NumericDifferentiator numeric(rate_hz);
  while (const auto sample = source.next()) {
    const TaskSample task = to_task_sample(*sample);
    if (acceleration == AccelerationSource::analytic) {
      consume(task);
    } else if (const auto ready = numeric.push(task)) {
      consume(*ready);
    }
  }
  while (const auto rest = numeric.drain()) consume(*rest);
  if (writer) writer->finish();
  return summary;
}

}  // namespace stiffpath::compensation
