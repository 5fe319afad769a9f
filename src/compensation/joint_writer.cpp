// CSV and binary joint-trajectory writers with large buffers and atomic output.
#include "stiffpath/compensation/joint_writer.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <algorithm>
#include <cstring>

#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::compensation {

OutputFormat parse_output_format(const std::string& text) {
  if (text == "csv") return OutputFormat::csv;
  if (text == "bin" || text == "binary") return OutputFormat::binary;
  throw Error("output format '" + text + "' is not one of csv, bin");
}

void append_fixed(std::string& out, double value, int decimals) {
  static constexpr std::array<double, 10> kPow = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
  const auto scaled = static_cast<long long>(std::llround(value * kPow[static_cast<std::size_t>(decimals)]));
  unsigned long long magnitude = scaled < 0 ? 0ULL - static_cast<unsigned long long>(scaled)
                                            : static_cast<unsigned long long>(scaled);
  char digits[24];
  int n = 0;
  do {
    digits[n++] = static_cast<char>('0' + magnitude % 10);
    magnitude /= 10;
  } while (magnitude != 0 || n <= decimals);
  if (scaled < 0) out.push_back('-');
  for (int i = n - 1; i >= 0; --i) {
    out.push_back(digits[i]);
    if (i == decimals && decimals > 0) out.push_back('.');
  }
}

namespace {
constexpr std::size_t kFlushBytes = 1 << 20;

class CsvWriter final : public JointWriter {
 public:
  explicit CsvWriter(const std::string& path) : file_(path) {
    buffer_.reserve(kFlushBytes + 4096);
    buffer_.append(kJointCsvHeader).push_back('\n');
  }
  void write(const JointCommand& c) override {
    append_fixed(buffer_, c.t_s, 6);
    for (double v : {c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y()}) {
      buffer_.push_back(',');
      append_fixed(buffer_, v, 9);
    }
    buffer_.append(c.laser_on ? ",1" : ",0");
    for (double v : {c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y()}) {
      buffer_.push_back(',');
      append_fixed(buffer_, v * 1e3, 6);
    }
    for (double v : {c.force_N.x(), c.force_N.y()}) {
      buffer_.push_back(',');
      append_fixed(buffer_, v, 4);
    }
    buffer_.push_back(',');
    append_fixed(buffer_, c.line, 0);
    buffer_.push_back('\n');
    if (buffer_.size() >= kFlushBytes) flush();
  }
  void finish() override {
    flush();
    file_.commit();
  }

 private:
  void flush() {
    file_.stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }
  core::AtomicFile file_;
  std::string buffer_;
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

class BinaryWriter final : public JointWriter {
 public:
  BinaryWriter(const std::string& path, double rate_hz, const std::string& mechanism) : file_(path) {
    buffer_.reserve(kFlushBytes + kBinaryRecordBytes);
    std::array<char, kBinaryHeaderBytes> header{};
    header_into(header, rate_hz, mechanism, 0);
    file_.stream().write(header.data(), header.size());
    rate_hz_ = rate_hz;
    mechanism_ = mechanism;
  }
  void write(const JointCommand& c) override {
    std::array<char, kBinaryRecordBytes> record{};
    char* p = record.data();
    for (double v : {c.t_s, c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y(), c.qdd_rad_s2.x(),
                     c.qdd_rad_s2.y(), c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y(),
                     c.force_N.x(), c.force_N.y()}) {
      put(p, v);
    }
    put(p, static_cast<std::int32_t>(c.line));
    put(p, static_cast<std::uint8_t>(c.laser_on ? 1 : 0));
    buffer_.append(record.data(), record.size());
    ++count_;
    if (buffer_.size() >= kFlushBytes) flush();
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
    file_.stream().write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }
  core::AtomicFile file_;
  std::string buffer_;
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

}  // namespace stiffpath::compensation
