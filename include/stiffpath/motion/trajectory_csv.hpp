// Sampled trajectories to CSV (units in the column names) and the summary of a sampled job.
#pragma once

#include <cstdint>
#include <filesystem>
#include <fmt/format.h>
#include <ostream>

#include "stiffpath/motion/sampler.hpp"

namespace stiffpath::motion {

//! Peaks over the samples of a job (what `stiffpath plan` prints).
struct TrajectorySummary {
  double duration_s = 0.0;              //!< time of the last sample (s)
  std::uint64_t samples = 0;
  double peak_velocity_m_s = 0.0;       //!< largest |v| (m/s)
  double peak_acceleration_m_s2 = 0.0;  //!< largest |a| (m/s²), centripetal part included
  double peak_jerk_m_s3 = 0.0;          //!< largest |j| (m/s³)
  double laser_on_s = 0.0;              //!< samples with the laser on × the sample period (s)
  double laser_full_power_s = 0.0;      //!< Σ power × the sample period: the time at full power giving the same energy (s)
  double peak_power = 0.0;              //!< largest power fraction (0..1)
};

//! Accumulates a TrajectorySummary one sample at a time.
class SummaryAccumulator {
 public:
  explicit SummaryAccumulator(double rate_hz) : period_s_(1.0 / rate_hz) {}
  void add(const TrajectorySample& sample) noexcept;
  [[nodiscard]] const TrajectorySummary& summary() const noexcept { return summary_; }

 private:
  double period_s_;
  TrajectorySummary summary_;
};

//! The CSV header: time, position, velocity, acceleration and jerk in mm-based units, the laser
//! state (0/1), its power as a fraction of full power (0..1, 0 when off, M4 scaled by the speed)
//! and the source G-code line.
inline constexpr const char* trajectory_csv_header =
    "t_s,x_mm,y_mm,vx_mm_s,vy_mm_s,ax_mm_s2,ay_mm_s2,jx_mm_s3,jy_mm_s3,laser,power,line";

//! Formats samples as CSV rows into a buffer that is flushed to the stream in large blocks.
//! Decimals: t 7, position and velocity 6 (1 nm, 1 nm/s), acceleration 4, jerk 2, power 6.
class TrajectoryCsvWriter {
 public:
  explicit TrajectoryCsvWriter(std::ostream& out);  //!< writes the header line
  void write(const TrajectorySample& sample);
  void flush();  //!< writes what is buffered; call before closing the stream

 private:
  std::ostream& out_;
  fmt::memory_buffer buffer_;
};

//! Pulls every sample from `samples` and writes them to `path` through core::AtomicFile: the file
//! appears only when all went well. Returns the summary. Throws stiffpath::Error on I/O failure.
TrajectorySummary write_trajectory_csv(SampleSource& samples, double rate_hz, const std::filesystem::path& path);
//! Pulls every sample and only summarises them.
TrajectorySummary summarize(SampleSource& samples, double rate_hz);

}  // namespace stiffpath::motion
