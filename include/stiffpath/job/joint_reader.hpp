// Reading joint trajectories written by `stiffpath run` (CSV or the binary format), streaming.
#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/core/csv.hpp"

namespace stiffpath::job {

using compensation::Vec2;

//! Largest time between two records of a joint file (s): `run` writes at 1 Hz or faster, and the twin
//! steps every interval at its own rate, so a larger gap is refused where it is read.
inline constexpr double max_record_gap_s = 10.0;
//! Largest |t_s| of a record (s): 10^7 s, about 116 days.
inline constexpr double max_record_time_s = 1e7;

//! Reads a joint file sample by sample, as the JointCommands that were written (status ok; the
//! predicted deflection is not stored, and CSV files carry no α, so qdd stays zero there); the
//! format is recognised by the binary magic. Every bad value is an error naming the file and the
//! line and column (CSV) or the record number and byte offset (binary). Times must increase, by at most
//! max_record_gap_s; every value is finite and within generous physical bounds.
class JointReader {
 public:
  explicit JointReader(const std::string& path);
  ~JointReader();
  JointReader(const JointReader&) = delete;
  JointReader& operator=(const JointReader&) = delete;

  //! The next record, or nullopt at the end.
  std::optional<compensation::JointCommand> next();
  [[nodiscard]] bool binary() const noexcept { return binary_; }
  //! Sample rate from the binary header; from the first two CSV samples otherwise (0 until known).
  [[nodiscard]] double rate_hz() const noexcept { return rate_hz_; }
  [[nodiscard]] const std::string& mechanism() const noexcept { return mechanism_; }

 private:
  std::optional<compensation::JointCommand> next_csv();
  std::optional<compensation::JointCommand> next_binary();

  std::string path_;
  bool binary_ = false;
  std::ifstream in_;
  std::unique_ptr<core::CsvReader> csv_;
  std::size_t columns_[13] = {};
  std::uint64_t expected_ = 0, read_ = 0;
  double rate_hz_ = 0.0, first_t_ = 0.0, last_t_ = 0.0;
  std::string mechanism_;
};

}  // namespace stiffpath::job
