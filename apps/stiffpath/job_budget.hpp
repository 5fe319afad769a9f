// Output budget of a planned job: its sample count before writing, a --max-samples cap and the free disk space.
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "stiffpath/motion/trajectory_stream.hpp"

namespace stiffpath::cli {

//! Default cap on the samples one job writes: 20 million, 2 h 46 min 40 s at 2 kHz.
inline constexpr std::uint64_t default_max_samples = 20'000'000;
//! The work bound of a job that writes no samples (plan or run without -o): a billion samples, 138 h
//! 53 min at 2 kHz, each made and checked but not kept (about 6 min of CPU for `plan`, 14 for `run`;
//! docs/reliability.md).
inline constexpr std::uint64_t max_unwritten_samples = 1'000'000'000;

//! Adds "--max-samples N" (default 20 M, on what is written) to a subcommand that plans G-code.
void add_max_samples_flag(CLI::App* cmd, std::uint64_t& max_samples);

//! How big one job's output is: bytes per sample, fixed header bytes, and the format's name for messages.
struct OutputEstimate {
  double bytes_per_sample = 0.0;
  double header_bytes = 0.0;
  const char* kind = "CSV";
};

//! Plans `job` without sampling it (motion::measure_plan) and refuses, before anything is written, a
//! job that writes its samples (`output` not empty) with more of them than `max_samples`, a job that
//! writes none with more than max_unwritten_samples (its work bound), or one whose output would not
//! fit on the file system holding `output` (empty or "-": not checked). The refusal names the sample
//! count, the duration, the estimated size and how to raise the cap; `noun` names the job ("plan",
//! "job"). `extra_samples`: what filters add at the end (their delay); `rest_samples`: how long they rest at
//! every stop (job::TaskSource restarts them there). Returns the size.
motion::PlanSize check_job_budget(const std::string& job, const motion::PlanOptions& options, std::uint64_t max_samples,
                                  const std::string& output, const OutputEstimate& estimate, const char* noun,
                                  std::uint64_t extra_samples = 0, std::uint64_t rest_samples = 0);

}  // namespace stiffpath::cli
