// CSV output of sampled trajectories (buffered, atomic) and the peak summary of a job.
#include "stiffpath/motion/trajectory_csv.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <iterator>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::motion {

void SummaryAccumulator::add(const TrajectorySample& sample) noexcept {
  summary_.duration_s = sample.t_s;
  ++summary_.samples;
  summary_.peak_velocity_m_s = std::max(summary_.peak_velocity_m_s, sample.velocity_m_s.norm());
  summary_.peak_acceleration_m_s2 = std::max(summary_.peak_acceleration_m_s2, sample.acceleration_m_s2.norm());
  summary_.peak_jerk_m_s3 = std::max(summary_.peak_jerk_m_s3, sample.jerk_m_s3.norm());
  if (sample.laser_on) summary_.laser_on_s += period_s_;
  summary_.laser_full_power_s += sample.power * period_s_;
  summary_.peak_power = std::max(summary_.peak_power, sample.power);
}

namespace {

constexpr std::size_t flush_bytes = 1 << 16;

// A fixed-point number with `decimals` digits and a trailing comma, formatted from the integer
// round(value·10^decimals) (several times faster than a floating-point format); values that round
// to zero print as 0 (never "-0.000"). Magnitudes beyond 9e15 units fall back to fmt.
void put(fmt::memory_buffer& buffer, double value, int decimals) {
  static constexpr double scale[] = {1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8};
  static constexpr std::int64_t unit[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
  const double scaled = std::round(value * scale[decimals]);
  if (!(std::abs(scaled) < 9e15)) {
    fmt::format_to(std::back_inserter(buffer), "{:.{}f},", value, decimals);
    return;
  }
  auto n = static_cast<std::int64_t>(scaled);
  if (n < 0) {
    buffer.push_back('-');
    n = -n;
  }
  const fmt::format_int whole(n / unit[decimals]);
  buffer.append(whole.data(), whole.data() + whole.size());
  if (decimals > 0) {
    buffer.push_back('.');
    char digits[8];
    std::int64_t fraction = n % unit[decimals];
    for (int k = decimals - 1; k >= 0; --k, fraction /= 10) digits[k] = static_cast<char>('0' + fraction % 10);
    buffer.append(digits, digits + decimals);
  }
  buffer.push_back(',');
}

}  // namespace

TrajectoryCsvWriter::TrajectoryCsvWriter(std::ostream& out) : out_(out) {
  out_ << trajectory_csv_header << '\n';
}

void TrajectoryCsvWriter::write(const TrajectorySample& s) {
  put(buffer_, s.t_s, 7);
  put(buffer_, units::m_to_mm(s.position_m.x()), 6);
  put(buffer_, units::m_to_mm(s.position_m.y()), 6);
  put(buffer_, units::m_to_mm(s.velocity_m_s.x()), 6);
  put(buffer_, units::m_to_mm(s.velocity_m_s.y()), 6);
  put(buffer_, units::m_to_mm(s.acceleration_m_s2.x()), 4);
  put(buffer_, units::m_to_mm(s.acceleration_m_s2.y()), 4);
  put(buffer_, units::m_to_mm(s.jerk_m_s3.x()), 2);
  put(buffer_, units::m_to_mm(s.jerk_m_s3.y()), 2);
  buffer_.push_back(s.laser_on ? '1' : '0');
  buffer_.push_back(',');
  put(buffer_, s.power, 6);
  fmt::format_to(std::back_inserter(buffer_), "{}\n", s.line);
  if (buffer_.size() >= flush_bytes) flush();
}

void TrajectoryCsvWriter::flush() {
  out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  buffer_.clear();
}

TrajectorySummary write_trajectory_csv(SampleSource& samples, double rate_hz, const std::filesystem::path& path) {
  core::AtomicFile file(path);
  TrajectoryCsvWriter writer(file.stream());
  SummaryAccumulator summary(rate_hz);
  while (auto sample = samples.next()) {
    writer.write(*sample);
    summary.add(*sample);
  }
  writer.flush();
  file.commit();
  return summary.summary();
}

TrajectorySummary summarize(SampleSource& samples, double rate_hz) {
  SummaryAccumulator summary(rate_hz);
  while (auto sample = samples.next()) summary.add(*sample);
  return summary.summary();
}

}  // namespace stiffpath::motion
