// The offline job: G-code samples → compensation → joint commands, streamed with flat memory.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "stiffpath/compensation/compensator.hpp"
#include "stiffpath/compensation/reference_filter.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/job/task_source.hpp"
#include "stiffpath/motion/sampler.hpp"
#include "stiffpath/motion/slowdown.hpp"

namespace stiffpath::job {

using compensation::JointCommand;
using compensation::TaskSample;

//! What a finished job reports.
struct JobSummary {
  double duration_s = 0.0;
  std::uint64_t samples = 0;
  double peak_deflection_m = 0.0;         //!< largest predicted |Δ|
  double peak_correction_m = 0.0;         //!< largest |p_cmd − p| = k·|Δ|
  double peak_force_N = 0.0;              //!< largest |F| = m·|a|
  double peak_joint_velocity_rad_s = 0.0;
  double peak_joint_acceleration_rad_s2 = 0.0;
  std::uint64_t samples_outside_grid = 0;  //!< samples where the model clamped or extrapolated
  std::optional<motion::SlowdownReport> slowdowns;  //!< the time lost to each limit, for a planned G-code program
};

//! Called every ~64k samples with the samples done and the current G-code line (for progress).
using Progress = std::function<void(std::uint64_t samples, int line)>;

//! Runs every sample of `source` through `compensator` and `writer` (may be null: summary only).
//! The calling thread plans; a second thread checks and writes the commands in order, and either
//! thread compensates (src/job/job_pipeline.hpp), so the job uses two cores. `writer` is
//! called from that second thread only, one command at a time, in order; `progress` from the
//! calling thread. On the first refused sample it throws stiffpath::Error "<job>:<line>: t = … s:
//! <quantity> …" naming the G-code line, the time and the value against its limit; the writer is
//! then not finished, so no output file appears. Memory does not depend on the job's length.
//! `filters` (optional, e.g. the moving average that makes the jerk continuous) act on the planned
//! samples, after the acceleration source and before compensation; the job then lasts their delay longer.
JobSummary run_job(motion::SampleSource& source, const compensation::Compensator& compensator, JointWriter* writer,
                   const std::string& job_label, double rate_hz,
                   AccelerationSource acceleration = AccelerationSource::analytic, const Progress& progress = {},
                   compensation::FilterChain* filters = nullptr, LaserDelays laser = {});

//! A sample the compensator refused: a stiffpath::Error located at its G-code line, with the step's status.
class Refusal : public Error {
 public:
  Refusal(const SourceLocation& where, const std::string& message, compensation::Status status)
      : Error(where, message), status_(status) {}
  [[nodiscard]] compensation::Status status() const noexcept { return status_; }

 private:
  compensation::Status status_;
};

//! Throws the Refusal for a refused command `c` (status not ok): "<job>:<line>: t = … s:
//! <quantity> <value> against <limit>", the message run_job gives, for other loops over step().
[[noreturn]] void throw_refusal(const JointCommand& c, const compensation::Compensator& compensator, const std::string& job_label);

//! The compensation input for one planned sample (snap 0: jerk-limited profiles have none a.e.).
TaskSample to_task_sample(const motion::TrajectorySample& sample) noexcept;

}  // namespace stiffpath::job
