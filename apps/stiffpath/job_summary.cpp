// The main job's summary in words and as JSON: every setting as the job resolved it, so nothing applied is unnamed.
#include "job_summary.hpp"

#include <fmt/format.h>

#include "commands.hpp"
#include "motion_flags.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::cli {

namespace {
std::string outside_text(const job::PreparedJob& job, std::uint64_t samples) {
  if (samples == 0 || !job.model) return {};
  const compliance::OutsidePolicy policy = job.model->outside_policy();
  const char* done = policy == compliance::OutsidePolicy::extrapolate ? "extrapolated" : "clamped";
  return fmt::format("{} samples outside the compliance model's measured region: the model was {} there", samples, done);
}
}  // namespace

nlohmann::json job_summary_json(const job::PreparedJob& job, const job::JobSummary& s, const std::string& output) {
  const job::JobSpec& spec = job.spec;
  const bool compensating = spec.compensate;
  nlohmann::json out = {{"job", job.program.label()},
          {"robot", spec.robot.name},
          {"model", job.model_label},
          {"compensation", compensating},
          {"gain", compensating ? spec.gain : 0.0},
          {"acceleration_source", core::enum_name(spec.acceleration)},
          {"method", compensating ? std::string(core::enum_name(spec.method)) : "none"},
          {"damping_ratio", tidy(*spec.damping_ratio)},
          {"smooth_ms", tidy(*spec.smooth_s * 1e3)},
          {"shaper", core::enum_name(spec.shaper)},
          {"filters", job.filters_text()},
          {"laser_on_delay_ms", tidy(*spec.laser_on_delay_s * 1e3)},
          {"laser_off_delay_ms", tidy(*spec.laser_off_delay_s * 1e3)},
          {"jerk_m_s3", tidy(spec.plan.limits.max_jerk_m_s3)},
          {"lowest_frequency_hz", job.lowest_frequency_hz > 0.0 ? nlohmann::json(tidy(job.lowest_frequency_hz)) : nlohmann::json(nullptr)},
          {"duration_s", tidy(s.duration_s)},
          {"samples", s.samples},
          {"rate_hz", tidy(spec.plan.rate_hz)},
          {"peak_deflection_um", tidy(units::m_to_um(s.peak_deflection_m))},
          {"peak_correction_um", tidy(units::m_to_um(s.peak_correction_m))},
          {"peak_force_n", tidy(s.peak_force_N)},
          {"peak_joint_velocity_rad_s", tidy(s.peak_joint_velocity_rad_s)},
          {"peak_joint_acceleration_rad_s2", tidy(s.peak_joint_acceleration_rad_s2)},
          {"samples_outside_grid", s.samples_outside_grid},
          {"output", output.empty() ? nlohmann::json(nullptr) : nlohmann::json(output)}};
  if (s.slowdowns) out["slowdowns"] = slowdowns_json(*s.slowdowns);
  return out;
}

void print_job_summary(std::FILE* out, const job::PreparedJob& job, const job::JobSummary& s, const std::string& output) {
  const job::JobSpec& spec = job.spec;
  if (spec.compensate) {
    fmt::print(out, "{}: compensated on {} with {}{}\n", job.program.label(), spec.robot.name, job.model_label,
               spec.gain != 1.0 ? fmt::format(" (gain {:g})", spec.gain) : "");
    fmt::print(out, "  {} compensation (damping ratio {:g}), jerk {:.0f} m/s^3\n", core::enum_name(spec.method),
               *spec.damping_ratio, spec.plan.limits.max_jerk_m_s3);
  } else {
    fmt::print(out, "{}: not compensated on {} (the planned path as it is), jerk {:.0f} m/s^3\n", job.program.label(),
               spec.robot.name, spec.plan.limits.max_jerk_m_s3);
  }
  fmt::print(out, "  reference filters: {}\n", job.filters_text());
  if (*spec.laser_on_delay_s != 0.0 || *spec.laser_off_delay_s != 0.0) {
    fmt::print(out, "  laser switched for its delays: on {:g} ms, off {:g} ms\n",
               *spec.laser_on_delay_s * 1e3, *spec.laser_off_delay_s * 1e3);
  }
  fmt::print(out, "  {} samples at {:g} Hz, duration {:.4f} s\n", s.samples, spec.plan.rate_hz, s.duration_s);
  fmt::print(out, "  peak D'Alembert force {:.1f} N, predicted deflection {:.1f} um, correction {:.1f} um\n", s.peak_force_N,
             units::m_to_um(s.peak_deflection_m), units::m_to_um(s.peak_correction_m));
  fmt::print(out, "  peak joint velocity {:.2f} rad/s, acceleration {:.1f} rad/s^2\n", s.peak_joint_velocity_rad_s,
             s.peak_joint_acceleration_rad_s2);
  if (const auto outside = outside_text(job, s.samples_outside_grid); !outside.empty()) fmt::print(out, "  {}\n", outside);
  if (s.slowdowns) print_slowdowns(out, *s.slowdowns);
  if (!output.empty()) fmt::print(out, "  wrote {}\n", output);
}

}  // namespace stiffpath::cli
