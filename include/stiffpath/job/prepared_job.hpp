// A JobSpec made ready to run: model loaded, jerk and filters resolved, size known; then run into a sink or pulled.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "stiffpath/job/job.hpp"
#include "stiffpath/job/job_spec.hpp"
#include "stiffpath/job/program.hpp"

namespace stiffpath::job {

//! A job ready to run: what prepare() resolved from a JobSpec. Runs any number of times.
struct PreparedJob {
  JobSpec spec;     //!< as resolved: plan.limits.max_jerk_m_s3, damping_ratio and smooth_s are set
  Program program;
  std::shared_ptr<const compliance::Model> model;  //!< null when there is none (not compensating, no data)
  std::string model_label = "none";                //!< "physical-spline fitted to …", a file, "thesis-oc"
  std::optional<compliance::Provenance> provenance;  //!< of a loaded or fitted model
  std::shared_ptr<const compensation::Compensator> compensator;
  double lowest_frequency_hz = 0.0;  //!< the tip's, over the job's region (when the jerk rule or a shaper needs it)
  motion::PlanSize size;             //!< samples and duration, the filters' delay included

  //! A fresh chain of the reference filters (they keep state: one per run).
  [[nodiscard]] compensation::FilterChain make_filters() const;
  //! The filters in words: "two moving averages of 4 ms (8 ms smoothing)", "zv shaper, …", or "none".
  [[nodiscard]] std::string filters_text() const;
};

//! Resolves `spec` for `program`: loads the model (the robot's own unless the spec names one), builds the
//! compensator, finds the tip's lowest natural frequency over the job's region when the jerk rule or a
//! shaper needs it, resolves the jerk, and plans the program once without sampling it to know its size.
//! Throws stiffpath::Error for a bad value (naming it and its range), a program the planner refuses, a
//! robot without compliance data when compensating, or a job beyond kMaxJobSamples.
PreparedJob prepare(JobSpec spec, Program program);

//! Refuses, before anything is written, a job whose output to `path` ("-", a FIFO or a device are not
//! measured) has more samples than spec.max_samples or would not fit on its file system (estimated from
//! the format's record size).
void check_output(const PreparedJob& job, const std::string& path);

//! Runs the job into `writer` (null: summary only) on two threads (run_job), with a fresh filter chain.
JobSummary run(const PreparedJob& job, JointWriter* writer, const Progress& progress = {});

//! The job's commands one at a time on the calling thread (the twin, bindings): throws the located
//! refusal of run_job at the first refused sample.
class CommandStream {
 public:
  explicit CommandStream(const PreparedJob& job);
  CommandStream(const CommandStream&) = delete;
  CommandStream& operator=(const CommandStream&) = delete;
  //! The next command; nullopt after the last.
  std::optional<compensation::JointCommand> next();

 private:
  const PreparedJob& job_;
  std::unique_ptr<motion::SampleSource> source_;
  compensation::FilterChain filters_;
  TaskSource tasks_;
};

}  // namespace stiffpath::job
