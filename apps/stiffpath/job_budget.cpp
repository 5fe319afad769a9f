// Output budget of a planned job: refuse before writing a job beyond --max-samples or beyond the free disk space.
#include "job_budget.hpp"

#include <fmt/format.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/core/output_budget.hpp"

namespace stiffpath::cli {

void add_max_samples_flag(CLI::App* cmd, std::uint64_t& max_samples) {
  cmd->add_option("--max-samples", max_samples,
                  "Refuse to write a job with more samples than this (20 M: 2 h 46 min at 2 kHz); counted before "
                  "writing. Without -o a job is only bounded by its work, 1e9 samples")
      ->capture_default_str()
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 50));
}

motion::PlanSize check_job_budget(const std::string& job, const motion::PlanOptions& options, std::uint64_t max_samples,
                                  const std::string& output, const OutputEstimate& estimate, const char* noun, std::uint64_t extra_samples,
                                  std::uint64_t rest_samples) {
  motion::PlanSize size = motion::measure_plan(job, options, rest_samples);
  // What filters after the planner add: their delay at the end, and their rests at the stops.
  extra_samples += size.rest_samples_added;
  size.samples += extra_samples;
  size.duration_s += static_cast<double>(extra_samples) / options.rate_hz;
  const double bytes = static_cast<double>(size.samples) * estimate.bytes_per_sample + estimate.header_bytes;
  if (output.empty()) {  // nothing is written: only the work is bounded
    if (size.samples > max_unwritten_samples) {
      throw Error(SourceLocation{job}, fmt::format("the {} has {} samples ({:.1f} s at {:g} Hz), more than the {} a job that "
                                                   "writes nothing may make (its work bound)",
                                                   noun, size.samples, size.duration_s, options.rate_hz, max_unwritten_samples));
    }
    return size;
  }
  if (size.samples > max_samples) {
    throw Error(SourceLocation{job}, fmt::format("the {} has {} samples ({:.1f} s at {:g} Hz, about {} of {}), more than "
                                                 "the cap of {}; raise it with --max-samples",
                                                 noun, size.samples, size.duration_s, options.rate_hz,
                                                 core::human_bytes(bytes), estimate.kind, max_samples));
  }
  core::check_free_space(output, bytes,
                         fmt::format("the {} has {} samples ({:.1f} s at {:g} Hz); free some space, write elsewhere "
                                     "or shorten the program",
                                     noun, size.samples, size.duration_s, options.rate_hz));
  return size;
}

}  // namespace stiffpath::cli
