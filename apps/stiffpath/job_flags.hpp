// The flags of the main job (`run`, and what compares with it), translated onto the library's job::JobSpec.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "motion_flags.hpp"
#include "robot_flags.hpp"
#include "stiffpath/job/job_spec.hpp"

namespace stiffpath::cli {

//! The job's flags as given; unset ones keep job::JobSpec's defaults.
struct JobFlags {
  std::string robot;
  ModelFlags model;
  bool thesis = false;
  bool no_compensation = false;
  std::optional<double> gain;
  std::string accel_source;
  std::string method;
  std::optional<double> damping_ratio;
  std::optional<double> smooth_ms;
  std::string shaper;
  std::string outside;
  std::string format = "csv";
  std::uint64_t max_samples = job::kDefaultMaxSamples;
  MotionFlags motion;
};

//! Registers every job flag on `cmd` (robot, model, --thesis, compensation, filters, output format and cap,
//! the motion flags).
void add_job_flags(CLI::App* cmd, JobFlags& flags);
//! The JobSpec the flags ask for. Throws stiffpath::Error "--flag: reason" for a bad value.
job::JobSpec job_spec(const JobFlags& flags);

}  // namespace stiffpath::cli
