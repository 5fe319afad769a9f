// CSV and binary joint-trajectory writers with large buffers and atomic output.
#include "stiffpath/job/joint_writer.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <algorithm>
#include <cstring>
#include <vector>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::job {

OutputFormat parse_output_format(const std::string& text) {
  if (text == "csv") return OutputFormat::csv;
  if (text == "bin" || text == "binary") return OutputFormat::binary;
  throw Error("output format '" + text + "' is not one of csv, bin");
}

namespace {
constexpr std::size_t kFlushBytes = 1 << 20;

// Rows are formatted straight into a fixed buffer that goes to the file whenever it passes kFlushBytes.
class CsvWriter final : public JointWriter {
 public:
  explicit CsvWriter(const std::string& path) : file_(path), buffer_(kFlushBytes + kMaxRowChars) {
    const std::string header = std::string(kJointCsvHeader) + "\n";
    file_.stream().write(header.data(), static_cast<std::streamsize>(header.size()));
  }
  void write(const JointCommand& c) override {
    char* p = buffer_.data() + used_;
    p = write_fixed(p, c.t_s, 6);
    for (double v : {c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y()}) {
      *p++ = ',';
      p = write_fixed(p, v, 9);
    }
    *p++ = ',';
    *p++ = c.laser_on ? '1' : '0';
    for (double v : {c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y()}) {
      *p++ = ',';
      p = write_fixed(p, v * 1e3, 6);
    }
    for (double v : {c.force_N.x(), c.force_N.y()}) {
      *p++ = ',';
      p = write_fixed(p, v, 4);
    }
    *p++ = ',';
    p = write_fixed(p, c.line, 0);
    *p++ = '\n';
    used_ = static_cast<std::size_t>(p - buffer_.data());
    if (used_ >= kFlushBytes) flush();
  }
  void finish() override {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kMaxRowChars = 13 * (kMaxFixedChars + 1) + 2;  // 13 cells, separators, laser
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
  BinaryWriter(const std::string& path, double rate_hz, const std::string& mechanism)
      : file_(path), buffer_(kBufferRecords * kBinaryRecordBytes), rate_hz_(rate_hz), mechanism_(mechanism) {
    std::array<char, kBinaryHeaderBytes> header{};
    header_into(header, rate_hz, mechanism, 0);
    file_.stream().write(header.data(), header.size());
  }
  void write(const JointCommand& c) override {
    if (used_ == buffer_.size()) flush();
    char* p = buffer_.data() + used_;
    for (double v : {c.t_s, c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y(), c.qdd_rad_s2.x(),
                     c.qdd_rad_s2.y(), c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y(),
                     c.force_N.x(), c.force_N.y()}) {
      put(p, v);
    }
    put(p, static_cast<std::int32_t>(c.line));
    put(p, static_cast<std::uint8_t>(c.laser_on ? 1 : 0));
    std::memset(p, 0, 3);  // padding
    used_ += kBinaryRecordBytes;
    ++count_;
  }
  void finish() override {
    flush();
    std::array<char, kBinaryHeaderBytes> header{};
    header_into(header, rate_hz_, mechanism_, count_);
    file_.stream().seekp(0);
    file_.stream().write(header.data(), header.size());
    file_.commit();
  }

 private:
  static constexpr std::size_t kBufferRecords = kFlushBytes / kBinaryRecordBytes;
  static void header_into(std::array<char, kBinaryHeaderBytes>& h, double rate_hz, const std::string& mechanism,
                          std::uint64_t count) {
    char* p = h.data();
    std::memcpy(p, kBinaryMagic, 8);
    p += 8;
    put(p, kBinaryVersion);
    put(p, kBinaryRecordBytes);
    put(p, rate_hz);
    put(p, count);
    std::memcpy(p, mechanism.data(), std::min<std::size_t>(mechanism.size(), 31));
  }
  void flush() {
    file_.stream().write(buffer_.data(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }
  core::AtomicFile file_;
  std::vector<char> buffer_;
  std::size_t used_ = 0;
  double rate_hz_ = 0.0;
  std::string mechanism_;
  std::uint64_t count_ = 0;
};
}  // namespace

std::unique_ptr<JointWriter> make_joint_writer(OutputFormat format, const std::string& path, double rate_hz,
                                               const std::string& mechanism) {
  if (format == OutputFormat::csv) return std::make_unique<CsvWriter>(path);
  return std::make_unique<BinaryWriter>(path, rate_hz, mechanism);
}

}  // namespace stiffpath::job
