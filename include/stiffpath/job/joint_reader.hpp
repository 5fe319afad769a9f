// Reading joint trajectories written by `stiffpath run` (CSV or the binary format), streaming.
#pragma once

#include <array>
#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/job/joint_record.hpp"

namespace stiffpath::job {

using compensation::Vec2;

//! Largest time between two records of a joint file (s): `run` writes at 1 Hz or faster, and the twin
//! steps every interval at its own rate, so a larger gap is refused where it is read.
inline constexpr double max_record_gap_s = 10.0;

//! Reads a joint file sample by sample, as the JointCommands that were written (status ok; the
//! predicted deflection is not stored). The format is recognised by the binary magic; binary
//! versions 1 and 2 are read, and CSV files written before α and power were recorded (α zero,
//! power 1 while the laser is on). Every bad value is an error naming the file and the line and
//! column (CSV) or the record number and byte offset (binary). Times must increase, by at most
//! max_record_gap_s; every value is finite and within its field's bounds (kJointFields).
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
  //! The robot the file was written for (binary header, CSV comment line); empty when not recorded.
  [[nodiscard]] const std::string& mechanism() const noexcept { return mechanism_; }
  //! Its geometry hash (kinematics::Robot::geometry_hash); empty when not recorded (binary version 1).
  [[nodiscard]] const std::string& geometry_hash() const noexcept { return geometry_hash_; }
  //! Binary format version (1 or 2); 0 for CSV.
  [[nodiscard]] std::uint32_t version() const noexcept { return version_; }

 private:
  std::optional<compensation::JointCommand> next_csv();
  std::optional<compensation::JointCommand> next_binary();
  void read_csv_comment(const std::string& path);

  std::string path_;
  bool binary_ = false;
  std::ifstream in_;
  std::unique_ptr<core::CsvReader> csv_;
  std::array<std::optional<std::size_t>, kJointFields.size()> columns_;  // CSV column of each field, if present
  std::uint32_t version_ = 0, record_bytes_ = 0;
  std::uint64_t expected_ = 0, read_ = 0;
  double rate_hz_ = 0.0, first_t_ = 0.0, last_t_ = 0.0;
  std::string mechanism_, geometry_hash_;
};

//! Every command of a joint file, in memory: at most `max_records` (refused beyond, "LIMIT", naming the file), and
//! refused when the file records a geometry other than `geometry_hash` (when both are known: empty skips the check).
std::vector<compensation::JointCommand> read_joint_commands(const std::string& path, const std::string& geometry_hash,
                                                            std::size_t max_records);

}  // namespace stiffpath::job
