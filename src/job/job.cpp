// run_job: the streaming offline job (planning here, compensation and writing in a two-thread pipeline), its summary and located errors.
#include "stiffpath/job/job.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fmt/format.h>

#include "job_pipeline.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::job {

TaskSample to_task_sample(const motion::TrajectorySample& s) noexcept {
  TaskSample t;
  t.t_s = s.t_s;
  t.position_m = s.position_m;
  t.velocity_m_s = s.velocity_m_s;
  t.acceleration_m_s2 = s.acceleration_m_s2;
  t.jerk_m_s3 = s.jerk_m_s3;
  t.laser_on = s.laser_on;
  t.power = s.power;
  t.line = s.line;
  return t;
}

// The refusal of one sample as an error message naming the quantity, its value and its limit.
void throw_refusal(const JointCommand& c, const compensation::Compensator& comp, const std::string& job) {
  using compensation::Status;
  const SourceLocation where{job, c.line};
  const std::string when = fmt::format("t = {:.4f} s", c.t_s);
  const auto& spec = comp.robot();
  const auto joint = [&]() -> const kinematics::JointLimit& { return spec.joints[static_cast<std::size_t>(std::max(c.joint, 0))]; };
  const int j = std::max(c.joint, 0);
  switch (c.status) {
    case Status::unreachable:
      throw Refusal(where, fmt::format("{}: corrected target (x = {:.4f} mm, y = {:.4f} mm) is not reachable: {}", when,
                                     units::m_to_mm(c.command_m.x()), units::m_to_mm(c.command_m.y()),
                                     comp.five_bar().explain(c.command_m)), c.status);
    case Status::joint_position:
      throw Refusal(where, fmt::format("{}: joint {} position {:.3f} deg outside [{:.1f}, {:.1f}] deg", when, joint().name,
                                     units::rad_to_deg(c.q_rad[j]), units::rad_to_deg(joint().min_rad),
                                     units::rad_to_deg(joint().max_rad)), c.status);
    case Status::joint_velocity:
      throw Refusal(where, fmt::format("{}: joint {} velocity {:.2f} rad/s exceeds the limit {:.2f} rad/s", when,
                                     joint().name, c.qd_rad_s[j], joint().max_velocity_rad_s), c.status);
    case Status::joint_acceleration:
      throw Refusal(where, fmt::format("{}: joint {} acceleration {:.1f} rad/s^2 exceeds the limit {:.1f} rad/s^2", when,
                                     joint().name, c.qdd_rad_s2[j], joint().max_acceleration_rad_s2), c.status);
    case Status::outside_grid: {
      const compliance::GridBounds b = comp.model().bounds();
      throw Refusal(where, fmt::format("{}: (x = {:.4f} mm, y = {:.4f} mm) is more than {:g} mm outside the compliance "
                                     "model's measured region x [{:.3f}, {:.3f}] mm, y [{:.3f}, {:.3f}] mm (use "
                                     "--outside clamp or extrapolate to go on anyway)",
                                     when, units::m_to_mm(c.target_m.x()), units::m_to_mm(c.target_m.y()),
                                     units::m_to_mm(compliance::kOutsideMargin_m), units::m_to_mm(b.x_min),
                                     units::m_to_mm(b.x_max), units::m_to_mm(b.y_min), units::m_to_mm(b.y_max)), c.status);
    }
    case Status::not_finite: throw Refusal(where, when + ": the planned sample is not finite", c.status);
    case Status::ok: break;
  }
  throw Refusal(where, when + ": " + compensation::describe(c.status), c.status);
}

JobSummary run_job(motion::SampleSource& source, const compensation::Compensator& compensator, JointWriter* writer,
                   const std::string& job_label, double rate_hz, AccelerationSource acceleration,
                   const Progress& progress, compensation::FilterChain* filters, LaserDelays laser) {
  TaskSource tasks(source, rate_hz, acceleration, filters, laser);

  // This thread plans; compensation, checks and writing go through the two-thread pipeline. An
  // error of the planner (a bad G-code line further on) is reported only after the samples planned
  // before it: a refusal among them comes first, as when one sample at a time was planned and used.
  detail::JobPipeline pipeline(compensator, writer);
  std::exception_ptr planning_error;
  std::uint64_t planned = 0;
  bool more = true;
  while (more) {
    detail::JobBlock* block = pipeline.acquire();
    if (!block) break;  // refused or the writer failed: the pipeline says which below
    std::size_t count = 0;
    try {
      while (count < block->tasks.size() && (more = tasks.next(block->tasks[count]))) {
        if ((++planned & 0xffff) == 0 && progress) progress(planned, block->tasks[count].line);
        ++count;
      }
    } catch (...) {
      planning_error = std::current_exception();
      more = false;
    }
    pipeline.release(block, count);
  }
  pipeline.close();
  if (pipeline.refusal()) throw_refusal(*pipeline.refusal(), compensator, job_label);
  if (pipeline.writer_error()) std::rethrow_exception(pipeline.writer_error());
  if (planning_error) std::rethrow_exception(planning_error);
  if (writer) writer->finish();

  const detail::JobTotals& t = pipeline.totals();
  JobSummary summary;
  summary.duration_s = t.last_t_s;
  summary.samples = t.samples;
  summary.peak_deflection_m = std::sqrt(t.deflection2);  // sqrt is monotonic and correctly rounded:
  summary.peak_correction_m = std::sqrt(t.correction2);  // the same numbers as a norm per sample
  summary.peak_force_N = std::sqrt(t.force2);
  summary.peak_joint_velocity_rad_s = t.joint_velocity;
  summary.peak_joint_acceleration_rad_s2 = t.joint_acceleration;
  summary.samples_outside_grid = t.outside_grid;
  return summary;
}

}  // namespace stiffpath::job
