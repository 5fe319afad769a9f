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

// The text of a value outside its field's bounds (`lo`, `hi` in the unit of `name`).
std::string out_of_range(std::string_view name, double v, double lo, double hi) {
  if (lo == -hi) return fmt::format("RANGE: {} = {:g} is beyond ±{:g}", name, v, hi);
  return fmt::format("RANGE: {} = {:g} is outside [{:g}, {:g}]", name, v, lo, hi);
}

// What a reader takes for a field the file lacks: zero, or the laser bit (power of files before power was recorded).
void set_absent(compensation::JointCommand& r, const JointField& f) {
  set_value(r, f, f.if_absent == IfAbsent::laser_bit && r.laser_on ? 1.0 : 0.0);
}
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
  for (std::size_t i = 0; i < kJointFields.size(); ++i) {
    const JointField& f = kJointFields[i];  // a column older files lack may be absent; every other is required
    columns_[i] = f.if_absent == IfAbsent::refused ? csv_->column(f.csv_name) : csv_->find_column(f.csv_name);
  }
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
  compensation::JointCommand r;
  for (std::size_t i = 0; i < kJointFields.size(); ++i) {
    const JointField& f = kJointFields[i];
    if (!columns_[i]) continue;
    const std::size_t col = *columns_[i];
    const double v = f.csv_text == CsvText::fixed ? csv_->number(col) : static_cast<double>(csv_->integer(col));
    const double lo = f.min_si * f.csv_per_si, hi = f.max_si * f.csv_per_si;
    if (f.csv_text == CsvText::flag && v != 0.0 && v != 1.0) csv_->fail(col, fmt::format("must be 0 or 1, got {}", v));
    if (!(v >= lo && v <= hi)) csv_->fail(col, out_of_range(f.csv_name, v, lo, hi));
    set_value(r, f, f.csv_per_si == 1.0 ? v : v * (1.0 / f.csv_per_si));
  }
  for (std::size_t i = 0; i < kJointFields.size(); ++i) {
    if (!columns_[i]) set_absent(r, kJointFields[i]);
  }
  const std::size_t t_column = *columns_[joint_field("t_s")];
  if (read_ > 0) {
    const double gap = r.t_s - last_t_;
    if (!(gap > 0.0)) {
      csv_->fail(t_column, fmt::format("ORDER: time does not increase ({:g} s after {:g} s)", r.t_s, last_t_));
    }
    if (gap > max_record_gap_s) {
      csv_->fail(t_column, fmt::format("RANGE: t_s = {:g} s is {:g} s after the previous record, more than the {:g} s "
                                          "a joint file may leave between records",
                                          r.t_s, gap, max_record_gap_s));
    }
  }
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
  const std::uint64_t header_bytes = version_ == 1 ? kBinaryV1HeaderBytes : kBinaryHeaderBytes;
  const auto fail = [&](const std::string& why) {
    throw Error(SourceLocation{path_}, fmt::format("record {} (byte {}): {}", read_ + 1,
                                                   header_bytes + read_ * record_bytes_, why));
  };
  compensation::JointCommand r;
  for (const JointField& f : kJointFields) {
    const int at = version_ == 1 ? f.offset_v1 : f.offset_v2;
    if (at < 0) continue;
    const char* p = record.data() + at;
    const double v = f.binary_type == BinaryType::f64 ? get<double>(p)
                     : f.binary_type == BinaryType::i32 ? static_cast<double>(get<std::int32_t>(p))
                                                        : static_cast<double>(get<std::uint8_t>(p));
    if (!std::isfinite(v)) fail(fmt::format("RANGE: {} is not finite ({})", f.si_name, v));
    if (!(v >= f.min_si && v <= f.max_si)) fail(out_of_range(f.si_name, v, f.min_si, f.max_si));
    set_value(r, f, v);
  }
  for (const JointField& f : kJointFields) {
    if ((version_ == 1 ? f.offset_v1 : f.offset_v2) < 0) set_absent(r, f);
  }
  if (read_ > 0 && !(r.t_s > last_t_)) fail(fmt::format("ORDER: time does not increase ({:g} s after {:g} s)", r.t_s, last_t_));
  if (read_ > 0 && r.t_s - last_t_ > max_record_gap_s) {
    fail(fmt::format("RANGE: t_s = {:g} s is {:g} s after the previous record, more than the {:g} s a joint file may leave "
                     "between records",
                     r.t_s, r.t_s - last_t_, max_record_gap_s));
  }
  last_t_ = r.t_s;
  ++read_;
  return r;
}

std::vector<compensation::JointCommand> read_joint_commands(const std::string& path, const std::string& geometry_hash,
                                                            std::size_t max_records) {
  JointReader reader(path);
  std::vector<compensation::JointCommand> out;
  while (auto c = reader.next()) {
    if (out.size() == max_records) {
      throw Error(SourceLocation{path}, fmt::format("LIMIT: more than {} joint records", max_records));
    }
    out.push_back(*c);
  }
  if (!geometry_hash.empty() && !reader.geometry_hash().empty() && reader.geometry_hash() != geometry_hash) {
    throw Error(SourceLocation{path}, fmt::format("the joint file was written for another robot geometry ({})",
                                                  reader.mechanism().empty() ? "unnamed" : reader.mechanism()));
  }
  return out;
}

}  // namespace stiffpath::job
