// Writers of joint trajectories: CSV for people and tools, a little-endian binary format for controllers.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "stiffpath/compensation/samples.hpp"
#include "stiffpath/core/enum_names.hpp"
#include "stiffpath/job/joint_record.hpp"

namespace stiffpath::job {

using compensation::JointCommand;
using compensation::TaskSample;
using compensation::Vec2;

//! How a joint trajectory is written (names at the edges: "csv", "bin").
enum class OutputFormat : std::uint8_t { csv, binary };

//! First line of a joint CSV, a comment recording how it was made, followed by
//! " rate_hz=<Hz> geometry_sha256=<hex, or - when unknown> robot=<name to the end of the line>".
inline constexpr const char* kJointCsvComment = "# stiffpath joints";
//! The CSV header (kJointCsvHeader), its numbers' decimals and the binary record are those of
//! kJointFields (joint_record.hpp).

//! Binary format (docs/compensation.md): a 128-byte header, then one 120-byte record per sample,
//! all little-endian.
//!   header: char[8] magic "SPJOINT\0", u32 version = 2, u32 record_bytes = 120, f64 rate_hz,
//!           u64 sample_count, char[32] robot name (NUL-padded), char[64] robot geometry SHA-256
//!           (lower-case hex, NUL-filled when unknown)
//!   record: kJointFields at their offset_v2, then zero padding to kBinaryRecordBytes
//! Version 1 (64-byte header without the geometry, 112-byte records without power) is still read.
inline constexpr char kBinaryMagic[8] = {'S', 'P', 'J', 'O', 'I', 'N', 'T', '\0'};
inline constexpr std::uint32_t kBinaryVersion = 2;
inline constexpr std::uint32_t kBinaryHeaderBytes = 128;
inline constexpr std::uint32_t kBinaryV1HeaderBytes = 64;

//! The robot a joint file is written for: its name and geometry hash (kinematics::Robot::geometry_hash).
struct JointFileRobot {
  std::string name;
  std::string geometry_sha256;
};

//! Streams commands to a file written atomically: the file appears under its name only when
//! finish() succeeds; if the writer is destroyed first (an error stopped the job), nothing is left.
class JointWriter {
 public:
  virtual ~JointWriter() = default;
  virtual void write(const JointCommand& command) = 0;
  //! Flushes, completes the header (binary: the sample count) and renames into place.
  virtual void finish() = 0;
};

//! Bytes of a joint file of `samples` samples in `format`: exact for the binary format (header and
//! records), an upper estimate for CSV (140 bytes a row: the thesis's jobs measure 125-135, plus 200
//! bytes of header), for refusing an output that cannot fit before it is written.
double estimated_joint_file_bytes(OutputFormat format, std::uint64_t samples) noexcept;

//! A writer for `path` in `format`; `rate_hz` and the robot go into the binary header or the CSV's
//! first comment line.
std::unique_ptr<JointWriter> make_joint_writer(OutputFormat format, const std::string& path, double rate_hz,
                                               const JointFileRobot& robot);

}  // namespace stiffpath::job

template <>
struct stiffpath::core::EnumNames<stiffpath::job::OutputFormat> {
  static constexpr std::string_view what = "joint file format";
  static constexpr std::array<std::pair<job::OutputFormat, std::string_view>, 2> names{
      {{job::OutputFormat::csv, "csv"}, {job::OutputFormat::binary, "bin"}}};
};
