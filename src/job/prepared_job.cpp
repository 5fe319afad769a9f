// prepare(): a JobSpec resolved into a runnable job (model, compensator, jerk, filters, size); run() and CommandStream.
#include "stiffpath/job/prepared_job.hpp"

#include <fmt/format.h>

#include <cmath>

#include "stiffpath/compensation/run_filters.hpp"
#include "stiffpath/compensation/tip_modes.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/job/laser_timing.hpp"

namespace stiffpath::job {

namespace {

void check_range(const char* what, double value, double low, double high) {
  if (!(value >= low && value <= high)) {  // NaN fails too
    throw Error(fmt::format("{}: must lie in {:g} … {:g}, got {}", what, low, high, value));
  }
}

void check_spec(const JobSpec& spec) {
  if (spec.robot.name.empty()) throw Error("job: no robot given (kinematics::load_robot)");
  check_range("compensation gain", spec.gain, 0.0, 10.0);
  if (spec.damping_ratio) check_range("damping ratio", *spec.damping_ratio, 0.0, 0.9);
  if (spec.smooth_s) check_range("smoothing width (s)", *spec.smooth_s, 0.0, 1.0);
  if (spec.shaper == compensation::FilterKind::smooth) {
    throw Error("reference shaper: expected none, zv or zvd, got 'smooth' (smoothing has its own width)");
  }
  if (spec.max_samples == 0) throw Error("max_samples: must be at least 1");
}

// The program's samples with the laser's switches moved by its delays (when it has any).
std::unique_ptr<motion::SampleSource> open_source(const PreparedJob& job) { return job.program.open(job.spec.plan); }

LaserDelays laser_delays(const JobSpec& spec) { return {*spec.laser_on_delay_s, *spec.laser_off_delay_s}; }

bool has_compliance_data(const JobSpec& spec) {
  const auto& c = spec.robot.compliance;
  return spec.model.given || !c.table.empty() || !c.model.empty() || !spec.model.request.model.empty();
}

}  // namespace

compensation::FilterChain PreparedJob::make_filters() const {
  compensation::RunFilterOptions options;
  options.smooth_s = *spec.smooth_s;
  options.shaper = spec.shaper;
  options.damping_ratio = *spec.damping_ratio;
  options.min_frequency_hz = lowest_frequency_hz;
  return compensation::make_run_filters(spec.plan.rate_hz, options, model, spec.robot.moving_mass_kg);
}

std::string PreparedJob::filters_text() const {
  std::string out;
  if (spec.shaper != compensation::FilterKind::none) {
    out = fmt::format("{} shaper (damping ratio {:g}, tip frequency from {:.1f} Hz)", core::enum_name(spec.shaper),
                      *spec.damping_ratio, lowest_frequency_hz);
  }
  if (*spec.smooth_s > 0.0) {
    if (!out.empty()) out += ", then ";
    out += fmt::format("two moving averages of {:g} ms ({:g} ms smoothing)", *spec.smooth_s * 0.5e3, *spec.smooth_s * 1e3);
  }
  return out.empty() ? "none" : out;
}

PreparedJob prepare(JobSpec spec, Program program) {
  check_spec(spec);
  PreparedJob job;
  job.spec = std::move(spec);
  job.program = std::move(program);
  JobSpec& s = job.spec;

  // The model: needed to compensate; loaded without compensation too when the robot has data, so that
  // the measured region is checked the same way (a robot without data can still run uncompensated).
  if (s.model.given) {
    if (s.outside && *s.outside != s.model.given->outside_policy()) {
      throw Error("outside policy: set it on the given model (it is shared), not in the job");
    }
    job.model = s.model.given;
    job.model_label = s.model.given_label;
  } else if (s.compensate || has_compliance_data(s)) {
    compliance::LoadedModel loaded = compliance::load_robot_model(s.robot, s.model.request);
    if (s.outside) loaded.model->set_outside_policy(*s.outside);
    job.model_label = loaded.label;
    job.provenance = std::move(loaded.provenance);
    job.model.reset(loaded.model.release());
  }
  s.damping_ratio = s.damping_ratio.value_or(s.robot.tip_damping_ratio);
  s.laser_on_delay_s = s.laser_on_delay_s.value_or(s.robot.laser_on_delay_s);
  s.laser_off_delay_s = s.laser_off_delay_s.value_or(s.robot.laser_off_delay_s);
  for (const double d : {*s.laser_on_delay_s, *s.laser_off_delay_s}) check_range("laser delay (s)", d, -0.05, 0.05);
  s.smooth_s = smoothing_s(s);
  job.compensator = std::make_shared<const compensation::Compensator>(
      s.robot, job.model,
      compensation::CompensatorOptions{.gain = s.gain,
                                       .enabled = s.compensate,
                                       .check_limits = s.check_limits,
                                       .method = s.method,
                                       .damping_ratio = s.damping_ratio});

  // The jerk rule and the shapers need the tip's lowest natural frequency over the job's region.
  if (s.jerk == JerkRule::tip_frequency || s.shaper != compensation::FilterKind::none) {
    if (!job.model) throw Error("the jerk from the tip's frequency and the shapers need the robot's compliance model");
    job.lowest_frequency_hz = compensation::lowest_natural_frequency_hz(*job.model, s.robot.moving_mass_kg,
                                                                         job.program.region(s.plan));
    if (!(job.lowest_frequency_hz > 0.0)) {
      throw Error(SourceLocation{job.program.label()}, "the compliance model gives the tip no natural frequency on this job");
    }
    if (s.jerk == JerkRule::tip_frequency) {
      s.plan.limits.max_jerk_m_s3 = s.plan.limits.max_acceleration_m_s2 * job.lowest_frequency_hz;
      s.jerk = JerkRule::planned;  // resolved: the plan now carries it
    }
  }

  const compensation::FilterChain filters = job.make_filters();
  const auto rests = static_cast<std::uint64_t>(filters.rest_samples());
  if (job.program.is_gcode()) {
    auto quiet = s.plan;
    quiet.gcode.on_warnings = nullptr;  // the run reports the program's warnings, once
    job.size = job.program.measure(quiet, rests);
  } else {
    job.size = job.program.measure(s.plan, rests);
  }
  // What the filters add: their delay at the end, and their rests at the stops (TaskSource).
  const std::uint64_t added = static_cast<std::uint64_t>(filters.delay_samples()) + job.size.rest_samples_added;
  if (job.size.samples > 0) {
    job.size.samples += added;
    job.size.duration_s += static_cast<double>(added) / s.plan.rate_hz;
  }
  if (job.size.samples > kMaxJobSamples) {
    throw Error(SourceLocation{job.program.label()},
                fmt::format("the job has {} samples ({:.1f} s at {:g} Hz), more than any job may have ({})",
                            job.size.samples, job.size.duration_s, s.plan.rate_hz, kMaxJobSamples));
  }
  return job;
}

void check_output(const PreparedJob& job, const std::string& path) {
  const auto& s = job.spec;
  const double bytes = estimated_joint_file_bytes(s.format, job.size.samples);
  const std::string what = fmt::format("the job has {} samples ({:.1f} s at {:g} Hz, about {} of {})", job.size.samples,
                                       job.size.duration_s, s.plan.rate_hz, core::human_bytes(bytes),
                                       s.format == OutputFormat::csv ? "joint CSV" : "binary joint records");
  if (job.size.samples > s.max_samples) {
    throw Error(SourceLocation{job.program.label()},
                fmt::format("{}, more than the cap of {}; raise it with --max-samples", what,
                            s.max_samples));
  }
  core::check_free_space(path, bytes, what + "; free some space, write elsewhere or shorten the program");
}

JobSummary run(const PreparedJob& job, JointWriter* writer, const Progress& progress) {
  const auto source = open_source(job);
  compensation::FilterChain filters = job.make_filters();
  JobSummary summary = run_job(*source, *job.compensator, writer, job.program.label(), job.spec.plan.rate_hz,
                               job.spec.acceleration, progress, &filters, laser_delays(job.spec));
  if (const motion::SlowdownReport* slowdowns = source->slowdowns()) summary.slowdowns = *slowdowns;
  return summary;
}

CommandStream::CommandStream(const PreparedJob& job)
    : job_(job),
      source_(open_source(job)),
      filters_(job.make_filters()),
      tasks_(*source_, job.spec.plan.rate_hz, job.spec.acceleration, &filters_, laser_delays(job.spec)) {}

std::optional<compensation::JointCommand> CommandStream::next() {
  compensation::TaskSample sample;
  if (!tasks_.next(sample)) return std::nullopt;
  const compensation::JointCommand c = job_.compensator->step(sample);
  if (c.status != compensation::Status::ok) throw_refusal(c, *job_.compensator, job_.program.label());
  return c;
}

}  // namespace stiffpath::job
