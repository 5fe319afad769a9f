// CSV and binary joint-trajectory writers with large buffers and atomic output.
#include "stiffpath/job/joint_writer.hpp"

#include <array>
#include <charconv>
#include <fmt/format.h>
#include <bit>
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/job/fixed_format.hpp"

namespace stiffpath::job {

double estimated_joint_file_bytes(OutputFormat format, std::uint64_t samples) noexcept {
  const auto n = static_cast<double>(samples);
  if (format == OutputFormat::binary) return kBinaryHeaderBytes + n * kBinaryRecordBytes;
  return 200.0 + 140.0 * n;
}

namespace {
constexpr std::size_t kFlushBytes = 1 << 20;

// Rows are formatted straight into a fixed buffer that goes to the file whenever it passes kFlushBytes.
class CsvWriter final : public JointWriter {
 public:
  CsvWriter(const std::string& path, double rate_hz, const JointFileRobot& robot)
      : file_(path), buffer_(kFlushBytes + kMaxRowChars) {
    const std::string header = fmt::format("{} rate_hz={} geometry_sha256={} robot={}\n{}\n", kJointCsvComment, rate_hz,
                                           robot.geometry_sha256.empty() ? "-" : robot.geometry_sha256, robot.name,
                                           kJointCsvHeader);
    file_.stream().write(header.data(), static_cast<std::streamsize>(header.size()));
  }
  void write(const JointCommand& c) override {
    char* p = write_row(buffer_.data() + used_, c, std::make_index_sequence<kJointFields.size()>{});
    *p++ = '\n';
    used_ = static_cast<std::size_t>(p - buffer_.data());
    if (used_ >= kFlushBytes) flush();
  }
  void finish() override {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kMaxRowChars = kJointFields.size() * (kMaxFixedChars + 1) + 2;  // cells, separators, newline
  // One cell per field, unrolled at compile time so that each field's accessor and format fold into straight code.
  template <std::size_t... I>
  static char* write_row(char* p, const JointCommand& c, std::index_sequence<I...>) {
    ((p = write_cell<I>(p, c)), ...);
    return p;
  }
  template <std::size_t I>
  static char* write_cell(char* p, const JointCommand& c) {
    constexpr JointField f = kJointFields[I];
    if constexpr (I > 0) *p++ = ',';
    const double v = value_of(c, f);
    if constexpr (f.csv_text == CsvText::flag) {
      *p++ = v != 0.0 ? '1' : '0';
      return p;
    } else if constexpr (f.csv_text == CsvText::integer) {
      return std::to_chars(p, p + 12, static_cast<int>(v)).ptr;
    } else if constexpr (f.csv_per_si != 1.0) {
      return write_fixed(p, v * f.csv_per_si, f.csv_decimals);
    } else {
      return write_fixed(p, v, f.csv_decimals);
    }
  }
  void flush() {
    file_.stream().write(buffer_.data(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }
  core::AtomicFile file_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
};

template <typename T>
void put(char*& p, T value) {
  if constexpr (std::endian::native == std::endian::big) {
    auto bytes = std::bit_cast<std::array<char, sizeof(T)>>(value);
    for (std::size_t i = 0; i < sizeof(T); ++i) p[i] = bytes[sizeof(T) - 1 - i];
  } else {
    std::memcpy(p, &value, sizeof(T));
  }
  p += sizeof(T);
}

// Records are encoded straight into a fixed buffer of whole records that goes to the file when full.
class BinaryWriter final : public JointWriter {
 public:
  BinaryWriter(const std::string& path, double rate_hz, const JointFileRobot& robot)
      : file_(path), buffer_(kBufferRecords * kBinaryRecordBytes), rate_hz_(rate_hz), robot_(robot) {
    std::array<char, kBinaryHeaderBytes> header{};
    header_into(header, rate_hz, robot, 0);
    file_.stream().write(header.data(), header.size());
  }
  void write(const JointCommand& c) override {
    if (used_ == buffer_.size()) flush();
    char* record = buffer_.data() + used_;
    put_fields(record, c, std::make_index_sequence<kJointFields.size()>{});
    std::memset(record + kBinaryRecordFieldBytes, 0, kBinaryRecordBytes - kBinaryRecordFieldBytes);  // padding
    used_ += kBinaryRecordBytes;
    ++count_;
  }
  void finish() override {
    flush();
    std::array<char, kBinaryHeaderBytes> header{};
    header_into(header, rate_hz_, robot_, count_);
    file_.stream().seekp(0);
    file_.stream().write(header.data(), header.size());
    file_.commit();
  }

 private:
  static constexpr std::size_t kBufferRecords = kFlushBytes / kBinaryRecordBytes;
  template <std::size_t... I>
  static void put_fields(char* record, const JointCommand& c, std::index_sequence<I...>) {
    (put_field<I>(record, c), ...);
  }
  template <std::size_t I>
  static void put_field(char* record, const JointCommand& c) {
    constexpr JointField f = kJointFields[I];
    char* p = record + f.offset_v2;
    const double v = value_of(c, f);
    if constexpr (f.binary_type == BinaryType::f64) put(p, v);
    if constexpr (f.binary_type == BinaryType::i32) put(p, static_cast<std::int32_t>(v));
    if constexpr (f.binary_type == BinaryType::u8) put(p, static_cast<std::uint8_t>(v != 0.0 ? 1 : 0));
  }
  static void header_into(std::array<char, kBinaryHeaderBytes>& h, double rate_hz, const JointFileRobot& robot,
                          std::uint64_t count) {
    char* p = h.data();
    std::memcpy(p, kBinaryMagic, 8);
    p += 8;
    put(p, kBinaryVersion);
    put(p, kBinaryRecordBytes);
    put(p, rate_hz);
    put(p, count);
    std::memcpy(p, robot.name.data(), std::min<std::size_t>(robot.name.size(), 31));
    p += 32;
    std::memcpy(p, robot.geometry_sha256.data(), std::min<std::size_t>(robot.geometry_sha256.size(), 64));
  }
  void flush() {
    file_.stream().write(buffer_.data(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }
  core::AtomicFile file_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
  double rate_hz_ = 0.0;
  JointFileRobot robot_;
  std::uint64_t count_ = 0;
};
}  // namespace

std::unique_ptr<JointWriter> make_joint_writer(OutputFormat format, const std::string& path, double rate_hz,
                                               const JointFileRobot& robot) {
  if (robot.name.size() > 31 || robot.name.find_first_of("\n\r") != std::string::npos) {
    throw Error(fmt::format("robot name '{}' cannot be recorded in a joint file (one line of at most 31 bytes)",
                            robot.name));
  }
  if (format == OutputFormat::csv) return std::make_unique<CsvWriter>(path, rate_hz, robot);
  return std::make_unique<BinaryWriter>(path, rate_hz, robot);
}

}  // namespace stiffpath::job
