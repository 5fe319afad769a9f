// JointReader: CSV and binary joint trajectories back into records, with located errors.
#include "stiffpath/job/joint_reader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::job {

namespace {
template <typename T>
T get(const char*& p) {
  std::array<char, sizeof(T)> bytes;
  std::memcpy(bytes.data(), p, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes.begin(), bytes.end());
  p += sizeof(T);
  return std::bit_cast<T>(bytes);
}

// What a joint record may hold: generous physical bounds, so that an absurd value (1e300) is refused
// where it enters instead of overflowing the twin. Same order as the binary record's 13 doubles.
constexpr double kMaxAbs[13] = {max_record_time_s, 1e3, 1e3, 1e6, 1e6, 1e9, 1e9, 1e3, 1e3, 1e3, 1e3, 1e9, 1e9};
constexpr const char* kBinaryNames[13] = {"t_s",        "theta1_rad", "theta2_rad", "omega1_rad_s", "omega2_rad_s",
                                          "alpha1_rad_s2", "alpha2_rad_s2", "x_m",  "y_m",          "xcmd_m",
                                          "ycmd_m",     "fx_n",       "fy_n"};

constexpr const char* kCsvColumns[13] = {"t_s",   "theta1_rad", "theta2_rad", "omega1_rad_s", "omega2_rad_s",
                                         "laser", "x_mm",       "y_mm",       "xcmd_mm",      "ycmd_mm",
                                         "fx_n",  "fy_n",       "line"};
// Columns that files written before they existed lack: α1, α2 (zero) and power (the laser bit).
constexpr const char* kOptionalCsvColumns[3] = {"alpha1_rad_s2", "alpha2_rad_s2", "power"};
}  // namespace

JointReader::JointReader(const std::string& path) : path_(path), in_(path, std::ios::binary) {
  if (!in_) throw Error(SourceLocation{path}, "cannot open file");
  std::array<char, kBinaryHeaderBytes> header{};
  in_.read(header.data(), header.size());
  const auto got = static_cast<std::size_t>(in_.gcount());
  binary_ = got >= 8 && std::memcmp(header.data(), kBinaryMagic, 8) == 0;
  if (binary_) {
    const char* p = header.data() + 8;
    version_ = got >= 16 ? get<std::uint32_t>(p) : 0;
    const auto record = got >= 16 ? get<std::uint32_t>(p) : 0;
    const bool v1 = version_ == 1 && record == kBinaryV1RecordBytes && got >= kBinaryV1HeaderBytes;
    const bool v2 = version_ == kBinaryVersion && record == kBinaryRecordBytes && got == kBinaryHeaderBytes;
    if (!v1 && !v2) {
      throw Error(SourceLocation{path}, fmt::format("binary joint file version {} with {}-byte records; this stiffpath "
                                                    "reads versions 1 ({}-byte records) and {} ({}-byte records)",
                                                    version_, record, kBinaryV1RecordBytes, kBinaryVersion,
                                                    kBinaryRecordBytes));
    }
    record_bytes_ = record;
    rate_hz_ = get<double>(p);
    expected_ = get<std::uint64_t>(p);
    if (!(rate_hz_ >= 0.1 && rate_hz_ <= 1e6)) {
      throw Error(SourceLocation{path}, fmt::format("header (byte 16): RANGE: rate {:g} Hz is outside [0.1, 1e6] Hz", rate_hz_));
    }
    mechanism_.assign(p, strnlen(p, 32));
    p += 32;
    if (v2) {
      geometry_hash_.assign(p, strnlen(p, 64));
    } else {  // version 1: records start after its 64-byte header
      in_.clear();
      in_.seekg(kBinaryV1HeaderBytes);
    }
    return;
  }
  in_.close();
  read_csv_comment(path);
  csv_ = std::make_unique<core::CsvReader>(path);
  for (std::size_t i = 0; i < 13; ++i) columns_[i] = csv_->column(kCsvColumns[i]);
  for (std::size_t i = 0; i < 3; ++i) optional_[i] = csv_->find_column(kOptionalCsvColumns[i]);
}

// "# stiffpath joints rate_hz=… geometry_sha256=… robot=…" on the first line, if the file has it.
void JointReader::read_csv_comment(const std::string& path) {
  std::ifstream in(path);
  std::string line(core::max_csv_line_bytes + 1, '\0');
  in.getline(line.data(), static_cast<std::streamsize>(line.size()));  // at most one CSV line's worth
  line.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  while (!line.empty() && (line.back() == '\0' || line.back() == '\n')) line.pop_back();
  if (!line.starts_with(kJointCsvComment)) return;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto value = [&](std::string_view key) -> std::string {
    const auto at = line.find(std::string(" ") + std::string(key) + "=");
    if (at == std::string::npos) return {};
    const auto from = at + key.size() + 2;
    const auto to = key == "robot" ? std::string::npos : line.find(' ', from);
    return line.substr(from, to == std::string::npos ? std::string::npos : to - from);
  };
  // The rate it announces, checked as the binary header's is (the records' spacing then gives the rate).
  if (const auto at = line.find(" rate_hz="); at != std::string::npos) {
    const std::string text = value("rate_hz");
    const auto rate = core::parse_double(text);
    if (!rate || !(*rate >= 0.1 && *rate <= 1e6)) {
      throw Error(SourceLocation{path, 1, static_cast<int>(at + 10)},
                  fmt::format("RANGE: rate_hz={} is not a rate within [0.1, 1e6] Hz", text));
    }
    rate_hz_ = *rate;
  }
  mechanism_ = value("robot");
  geometry_hash_ = value("geometry_sha256");
  if (geometry_hash_ == "-") geometry_hash_.clear();
}

JointReader::~JointReader() = default;

std::optional<compensation::JointCommand> JointReader::next() { return binary_ ? next_binary() : next_csv(); }

std::optional<compensation::JointCommand> JointReader::next_csv() {
  if (!csv_->next()) return std::nullopt;
  const auto n = [&](int i) { return csv_->number(columns_[i]); };
  compensation::JointCommand r;
  r.t_s = n(0);
  r.q_rad = {n(1), n(2)};
  r.qd_rad_s = {n(3), n(4)};
  const long laser = csv_->integer(columns_[5]);
  if (laser != 0 && laser != 1) csv_->fail(columns_[5], fmt::format("must be 0 or 1, got {}", laser));
  r.laser_on = laser == 1;
  r.target_m = Vec2(n(6), n(7)) * 1e-3;
  r.command_m = Vec2(n(8), n(9)) * 1e-3;
  r.force_N = {n(10), n(11)};
  const long line = csv_->integer(columns_[12]);
  if (line < 0 || line > 2'000'000'000L) csv_->fail(columns_[12], fmt::format("RANGE: line {} is not a G-code line number", line));
  r.line = static_cast<int>(line);
  constexpr int csv_fields[11] = {0, 1, 2, 3, 4, 6, 7, 8, 9, 10, 11};
  const double csv_values[11] = {r.t_s, r.q_rad.x(), r.q_rad.y(), r.qd_rad_s.x(), r.qd_rad_s.y(), n(6), n(7), n(8), n(9),
                                 r.force_N.x(), r.force_N.y()};
  constexpr double csv_limits[11] = {max_record_time_s, 1e3, 1e3, 1e6, 1e6, 1e6, 1e6, 1e6, 1e6, 1e9, 1e9};
  for (int k = 0; k < 11; ++k) {
    if (std::abs(csv_values[k]) > csv_limits[k]) {
      csv_->fail(columns_[csv_fields[k]], fmt::format("RANGE: {} = {:g} is beyond ±{:g}", kCsvColumns[csv_fields[k]],
                                                      csv_values[k], csv_limits[k]));
    }
  }
  if (read_ > 0) {
    const double gap = r.t_s - last_t_;
    if (!(gap > 0.0)) {
      csv_->fail(columns_[0], fmt::format("ORDER: time does not increase ({:g} s after {:g} s)", r.t_s, last_t_));
    }
    if (gap > max_record_gap_s) {
      csv_->fail(columns_[0], fmt::format("RANGE: t_s = {:g} s is {:g} s after the previous record, more than the {:g} s "
                                          "a joint file may leave between records",
                                          r.t_s, gap, max_record_gap_s));
    }
  }
  if (optional_[0] && optional_[1]) r.qdd_rad_s2 = {csv_->number(*optional_[0]), csv_->number(*optional_[1])};
  r.power = optional_[2] ? csv_->number(*optional_[2]) : (r.laser_on ? 1.0 : 0.0);
  if (!(r.power >= 0.0 && r.power <= 1.0)) csv_->fail(*optional_[2], fmt::format("RANGE: power must be within [0, 1], got {}", r.power));
  last_t_ = r.t_s;
  if (read_ == 0) first_t_ = r.t_s;
  if (read_ == 1 && r.t_s > first_t_) rate_hz_ = 1.0 / (r.t_s - first_t_);
  ++read_;
  return r;
}

std::optional<compensation::JointCommand> JointReader::next_binary() {
  std::array<char, kBinaryRecordBytes> record{};
  in_.read(record.data(), record_bytes_);
  const auto got = in_.gcount();
  if (got == 0) {
    if (read_ != expected_) {
      throw Error(SourceLocation{path_}, fmt::format("header announces {} records, file holds {}", expected_, read_));
    }
    return std::nullopt;
  }
  if (got != static_cast<std::streamsize>(record_bytes_)) {
    throw Error(SourceLocation{path_}, fmt::format("record {} is truncated ({} of {} bytes)", read_ + 1, got,
                                                   record_bytes_));
  }
  const char* p = record.data();
  compensation::JointCommand r;
  double v[14] = {};
  const int doubles = version_ == 1 ? 13 : 14;  // version 2 adds the power
  for (int i = 0; i < doubles; ++i) v[i] = get<double>(p);
  const std::uint64_t header_bytes = version_ == 1 ? kBinaryV1HeaderBytes : kBinaryHeaderBytes;
  const auto fail = [&](const std::string& why) {
    throw Error(SourceLocation{path_}, fmt::format("record {} (byte {}): {}", read_ + 1,
                                                   header_bytes + read_ * record_bytes_, why));
  };
  if (!std::isfinite(v[13])) fail(fmt::format("RANGE: power is not finite ({})", v[13]));
  for (int k = 0; k < 13; ++k) {
    if (!std::isfinite(v[k])) fail(fmt::format("RANGE: {} is not finite ({})", kBinaryNames[k], v[k]));
    if (std::abs(v[k]) > kMaxAbs[k]) fail(fmt::format("RANGE: {} = {:g} is beyond ±{:g}", kBinaryNames[k], v[k], kMaxAbs[k]));
  }
  if (read_ > 0 && !(v[0] > last_t_)) fail(fmt::format("ORDER: time does not increase ({:g} s after {:g} s)", v[0], last_t_));
  if (read_ > 0 && v[0] - last_t_ > max_record_gap_s) {
    fail(fmt::format("RANGE: t_s = {:g} s is {:g} s after the previous record, more than the {:g} s a joint file may leave "
                     "between records",
                     v[0], v[0] - last_t_, max_record_gap_s));
  }
  last_t_ = v[0];
  r.t_s = v[0];
  r.q_rad = {v[1], v[2]};
  r.qd_rad_s = {v[3], v[4]};
  r.qdd_rad_s2 = {v[5], v[6]};
  r.target_m = {v[7], v[8]};
  r.command_m = {v[9], v[10]};
  r.force_N = {v[11], v[12]};
  r.line = get<std::int32_t>(p);
  r.laser_on = get<std::uint8_t>(p) != 0;
  r.power = version_ == 1 ? (r.laser_on ? 1.0 : 0.0) : v[13];
  if (!(r.power >= 0.0 && r.power <= 1.0)) {
    fail(fmt::format("RANGE: power = {:g} is outside [0, 1]", r.power));
  }
  ++read_;
  return r;
}

}  // namespace stiffpath::job
