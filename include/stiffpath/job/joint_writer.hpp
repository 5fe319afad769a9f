// Writers of joint trajectories: CSV for people and tools, a little-endian binary format for controllers.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "stiffpath/job/fixed_format.hpp"
#include "stiffpath/compensation/samples.hpp"

namespace stiffpath::job {

using compensation::JointCommand;
using compensation::TaskSample;
using compensation::Vec2;

enum class OutputFormat { csv, binary };
OutputFormat parse_output_format(const std::string& text);  //!< "csv" | "bin"; throws stiffpath::Error

//! CSV header of the joint trajectory (units in the names).
inline constexpr const char* kJointCsvHeader =
    "t_s,theta1_rad,theta2_rad,omega1_rad_s,omega2_rad_s,laser,x_mm,y_mm,xcmd_mm,ycmd_mm,fx_n,fy_n,line";

//! Binary format (docs/compensation.md): a 64-byte header, then one 112-byte record per sample,
//! all little-endian.
//!   header: char[8] magic "SPJOINT\0", u32 version = 1, u32 record_bytes = 112, f64 rate_hz,
//!           u64 sample_count, char[32] mechanism name (NUL-padded)
//!   record: f64 t_s, θ1, θ2 (rad), ω1, ω2 (rad/s), α1, α2 (rad/s²), x, y, x_cmd, y_cmd (m),
//!           Fx, Fy (N); i32 line; u8 laser; 3 bytes of zero padding
inline constexpr char kBinaryMagic[8] = {'S', 'P', 'J', 'O', 'I', 'N', 'T', '\0'};
inline constexpr std::uint32_t kBinaryVersion = 1;
inline constexpr std::uint32_t kBinaryHeaderBytes = 64;
inline constexpr std::uint32_t kBinaryRecordBytes = 112;

//! Streams commands to a file written atomically: the file appears under its name only when
//! finish() succeeds; if the writer is destroyed first (an error stopped the job), nothing is left.
class JointWriter {
 public:
  virtual ~JointWriter() = default;
  virtual void write(const JointCommand& command) = 0;
  //! Flushes, completes the header (binary: the sample count) and renames into place.
  virtual void finish() = 0;
};

//! A writer for `path` in `format`; `rate_hz` and `mechanism` go into the binary header.
std::unique_ptr<JointWriter> make_joint_writer(OutputFormat format, const std::string& path, double rate_hz,
                                               const std::string& mechanism);

}  // namespace stiffpath::job
