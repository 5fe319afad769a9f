// Round trips of the joint-file writers and reader (CSV, binary), fixed-point formatting, and corrupt files.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <random>
#include <sstream>

#include "cli_runner.hpp"
#include "stiffpath/job/joint_reader.hpp"
#include "stiffpath/job/joint_record.hpp"
#include "stiffpath/job/joint_writer.hpp"
#include "stiffpath/core/error.hpp"

namespace stiffpath::job {
using namespace stiffpath::compensation;  // NOLINT: the step is what the job runs
namespace {

std::vector<JointCommand> commands(int n) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<JointCommand> out;
  for (int k = 0; k < n; ++k) {
    JointCommand c;
    c.t_s = k / 2000.0;
    c.q_rad = {u(rng), u(rng)};
    c.qd_rad_s = {30 * u(rng), 30 * u(rng)};
    c.qdd_rad_s2 = {900 * u(rng), 900 * u(rng)};
    c.target_m = {0.22 + 0.05 * u(rng), 0.07 * u(rng)};
    c.command_m = c.target_m + Vec2(1e-4 * u(rng), 1e-4 * u(rng));
    c.force_N = {170 * u(rng), 170 * u(rng)};
    c.laser_on = k % 3 == 0;
    c.line = 10 + k / 7;
    out.push_back(c);
  }
  return out;
}

// The cells of a CSV data row.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(row);
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

std::string printf_fixed(double v, int decimals) {
  char text[400];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  const std::string out(text);
  // The writer drops the sign of a negative value that rounds to zero.
  return out.find_first_not_of("-0.") == std::string::npos && out[0] == '-' ? out.substr(1) : out;
}

// glibc's printf rounds the exact binary value correctly (ties to even): every cell must be its text
// (without the sign of a negative zero),
// and so parse back to the correctly rounded value, also for ties, tiny negatives and large magnitudes.
TEST(JointFiles, CsvNumbersAreCorrectlyRounded) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> values{0.0,      -0.0,      0.5,         -0.5,       2.5,      0.0005,    -0.0000000004,
                             0.125,    1.0000005, 0.1234565,   999.9999995, 1e15,    -123456789.0, 4.0000000005,
                             -2.0e-10, 1.0 / 3.0, 0.000000001, 5e-7,       0.0000015,
                             // exact ties at 6 and 9 decimals (odd/2^7, odd/2^10): printf rounds them to even
                             1.0 / 128, 3.0 / 128, -5.0 / 128, 1.0 / 1024, 3.0 / 1024, -7.0 / 1024,
                             // the two paths' border and the smallest numbers
                             999999999.9999999, -999999999.9999999, 1e9, 4.9e-324, -4.9e-324, 2.2250738585072014e-308};
  for (int i = 0; i < 20000; ++i) values.push_back(u(rng) * std::pow(10.0, (i % 9) - 3));
  std::vector<JointCommand> in;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const double v = values[k];
    JointCommand c;
    c.t_s = v;
    c.q_rad = {v, -v};
    c.qd_rad_s = {v * 3, v / 7};
    c.qdd_rad_s2 = {v * 11, -v};
    c.power = std::abs(u(rng));
    c.target_m = {v, v * 0.1};
    c.command_m = {-v, v};
    c.force_N = {v, v * 100};
    c.line = static_cast<int>(k);
    in.push_back(c);
  }
  test::TempDir dir;
  const auto path = (dir / "j.csv").string();
  auto writer = make_joint_writer(OutputFormat::csv, path, 2000.0, {"oc-gu", ""});
  for (const auto& c : in) writer->write(c);
  writer->finish();
  std::ifstream file(path);
  std::string row;
  std::getline(file, row);
  EXPECT_TRUE(row.starts_with(kJointCsvComment)) << row;
  std::getline(file, row);
  EXPECT_EQ(row, kJointCsvHeader);
  std::size_t k = 0;
  for (; std::getline(file, row); ++k) {
    ASSERT_LT(k, in.size());
    const JointCommand& c = in[k];
    const std::vector<std::pair<double, int>> expected{
        {c.t_s, 6},           {c.q_rad.x(), 9},          {c.q_rad.y(), 9},          {c.qd_rad_s.x(), 9},
        {c.qd_rad_s.y(), 9},  {c.qdd_rad_s2.x(), 6},     {c.qdd_rad_s2.y(), 6},     {c.laser_on ? 1.0 : 0.0, 0},
        {c.power, 6},         {c.target_m.x() * 1e3, 6}, {c.target_m.y() * 1e3, 6}, {c.command_m.x() * 1e3, 6},
        {c.command_m.y() * 1e3, 6}, {c.force_N.x(), 4},  {c.force_N.y(), 4},       {static_cast<double>(c.line), 0}};
    const auto got = cells(row);
    ASSERT_EQ(got.size(), expected.size()) << row;
    for (std::size_t i = 0; i < got.size(); ++i) {
      const auto [v, d] = expected[i];
      ASSERT_EQ(got[i], printf_fixed(v, d)) << "row " << k << " column " << i << " value " << v;
      // Within half a unit of the last place (the decimal rounding), plus the parse's own half ulp.
      ASSERT_LE(std::abs(std::stod(got[i]) - v), 0.5 * std::pow(10.0, -d) * (1 + 1e-9) + std::abs(v) * 1e-16) << v;
    }
  }
  EXPECT_EQ(k, in.size());
}

TEST(JointFiles, BinaryRoundTripIsExact) {
  test::TempDir dir;
  const auto path = (dir / "j.bin").string();
  const auto in = commands(5000);
  auto writer = make_joint_writer(OutputFormat::binary, path, 2000.0, {"oc-gu", ""});
  for (const auto& c : in) writer->write(c);
  writer->finish();
  EXPECT_EQ(std::filesystem::file_size(path), kBinaryHeaderBytes + kBinaryRecordBytes * in.size());
  JointReader reader(path);
  EXPECT_TRUE(reader.binary());
  EXPECT_EQ(reader.rate_hz(), 2000.0);
  EXPECT_EQ(reader.mechanism(), "oc-gu");
  std::size_t k = 0;
  while (auto r = reader.next()) {
    ASSERT_LT(k, in.size());
    EXPECT_EQ(r->q_rad, in[k].q_rad);
    EXPECT_EQ(r->qdd_rad_s2, in[k].qdd_rad_s2);
    EXPECT_EQ(r->command_m, in[k].command_m);
    EXPECT_EQ(r->line, in[k].line);
    EXPECT_EQ(r->laser_on, in[k].laser_on);
    ++k;
  }
  EXPECT_EQ(k, in.size());
}

TEST(JointFiles, CsvRoundTripKeepsTheWrittenPrecision) {
  test::TempDir dir;
  const auto path = (dir / "j.csv").string();
  const auto in = commands(3000);
  auto writer = make_joint_writer(OutputFormat::csv, path, 2000.0, {"oc-gu", ""});
  for (const auto& c : in) writer->write(c);
  writer->finish();
  JointReader reader(path);
  EXPECT_FALSE(reader.binary());
  std::size_t k = 0;
  while (auto r = reader.next()) {
    EXPECT_NEAR(r->q_rad.x(), in[k].q_rad.x(), 0.6e-9);           // 9 decimals
    EXPECT_NEAR(r->target_m.y(), in[k].target_m.y(), 0.6e-9);     // 6 decimals of mm
    EXPECT_NEAR(r->force_N.x(), in[k].force_N.x(), 0.6e-4);
    EXPECT_EQ(r->laser_on, in[k].laser_on);
    ++k;
  }
  EXPECT_EQ(k, in.size());
  EXPECT_NEAR(reader.rate_hz(), 2000.0, 1e-6);
}

TEST(JointFiles, UnfinishedWriterLeavesNoFile) {
  test::TempDir dir;
  {
    auto writer = make_joint_writer(OutputFormat::csv, (dir / "j.csv").string(), 2000.0, {"oc-gu", ""});
    for (const auto& c : commands(10)) writer->write(c);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(JointFiles, CorruptFilesAreReportedWithTheirPlace) {
  test::TempDir dir;
  const auto path = (dir / "j.bin").string();
  auto writer = make_joint_writer(OutputFormat::binary, path, 2000.0, {"oc-gu", ""});
  for (const auto& c : commands(3)) writer->write(c);
  writer->finish();
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 10);
  JointReader reader(path);
  EXPECT_TRUE(reader.next().has_value());
  EXPECT_TRUE(reader.next().has_value());
  try {
    (void)reader.next();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("record 3 is truncated"), std::string::npos) << e.what();
  }
  test::write_text(dir / "bad.csv", std::string(kJointCsvHeader) + "\n0,0.1,0.2,0,0,0,0,2,1,200,0,200,0,0,0,5\n");
  JointReader csv((dir / "bad.csv").string());
  try {
    (void)csv.next();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("column 'laser': must be 0 or 1, got 2"), std::string::npos) << e.what();
  }
}

TEST(JointFiles, BothFormatsRecordTheRobotPowerAndAccelerations) {
  test::TempDir dir;
  const std::string hash(64, 'a');
  for (const auto format : {OutputFormat::csv, OutputFormat::binary}) {
    const auto path = (dir / (format == OutputFormat::csv ? "j.csv" : "j.bin")).string();
    auto in = commands(50);
    for (std::size_t k = 0; k < in.size(); ++k) in[k].power = in[k].laser_on ? 0.25 + 0.01 * static_cast<double>(k) : 0.0;
    auto writer = make_joint_writer(format, path, 2000.0, {"my robot 2", hash});
    for (const auto& c : in) writer->write(c);
    writer->finish();
    JointReader reader(path);
    EXPECT_EQ(reader.mechanism(), "my robot 2");
    EXPECT_EQ(reader.geometry_hash(), hash);
    std::size_t k = 0;
    while (auto r = reader.next()) {
      EXPECT_NEAR(r->power, in[k].power, 0.6e-6);
      EXPECT_NEAR(r->qdd_rad_s2.x(), in[k].qdd_rad_s2.x(), 0.6e-6);
      EXPECT_NEAR(r->qdd_rad_s2.y(), in[k].qdd_rad_s2.y(), 0.6e-6);
      ++k;
    }
    EXPECT_EQ(k, in.size());
  }
}

// A version-1 file, encoded here field by field from the layout version 1 documented (64-byte header,
// 112-byte records without power), still reads: power is the laser bit, the geometry unknown.
TEST(JointFiles, VersionOneBinaryFilesStillRead) {
  test::TempDir dir;
  const auto in = commands(7);
  std::string bytes("SPJOINT", 8);
  const auto put = [&bytes](const auto value) { bytes.append(reinterpret_cast<const char*>(&value), sizeof value); };
  put(std::uint32_t{1});
  put(std::uint32_t{112});
  put(2000.0);
  put(std::uint64_t{in.size()});
  std::string name("sc-gl");
  name.resize(32, '\0');
  bytes += name;
  ASSERT_EQ(bytes.size(), 64U);
  for (const auto& c : in) {
    for (double v : {c.t_s, c.q_rad.x(), c.q_rad.y(), c.qd_rad_s.x(), c.qd_rad_s.y(), c.qdd_rad_s2.x(),
                     c.qdd_rad_s2.y(), c.target_m.x(), c.target_m.y(), c.command_m.x(), c.command_m.y(),
                     c.force_N.x(), c.force_N.y()}) {
      put(v);
    }
    put(std::int32_t{c.line});
    put(std::uint8_t{c.laser_on ? std::uint8_t{1} : std::uint8_t{0}});
    bytes.append(3, '\0');
  }
  test::write_text(dir / "v1.bin", bytes);
  JointReader reader((dir / "v1.bin").string());
  EXPECT_EQ(reader.version(), 1U);
  EXPECT_EQ(reader.mechanism(), "sc-gl");
  EXPECT_TRUE(reader.geometry_hash().empty());
  std::size_t k = 0;
  while (auto r = reader.next()) {
    EXPECT_EQ(r->t_s, in[k].t_s);
    EXPECT_EQ(r->q_rad, in[k].q_rad);
    EXPECT_EQ(r->force_N, in[k].force_N);
    EXPECT_EQ(r->line, in[k].line);
    EXPECT_EQ(r->power, in[k].laser_on ? 1.0 : 0.0);
    ++k;
  }
  EXPECT_EQ(k, in.size());
  // An unknown version is refused, naming the versions this build reads.
  bytes[8] = 7;
  test::write_text(dir / "v7.bin", bytes);
  try {
    JointReader bad((dir / "v7.bin").string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("version 7"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("reads versions 1"), std::string::npos) << e.what();
  }
}

// A CSV from before the robot, α and power were recorded: no robot, α zero, power from the laser bit.
TEST(JointFiles, OlderCsvFilesStillRead) {
  test::TempDir dir;
  test::write_text(dir / "old.csv",
                   "t_s,theta1_rad,theta2_rad,omega1_rad_s,omega2_rad_s,laser,x_mm,y_mm,xcmd_mm,ycmd_mm,fx_n,fy_n,line\n"
                   "0,0.1,0.2,0,0,1,200,0,200,0,0,0,5\n0.0005,0.1,0.2,0,0,0,200,0,200,0,0,0,6\n");
  JointReader reader((dir / "old.csv").string());
  EXPECT_TRUE(reader.mechanism().empty());
  const auto a = reader.next(), b = reader.next();
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->power, 1.0);
  EXPECT_EQ(b->power, 0.0);
  EXPECT_EQ(a->qdd_rad_s2, Vec2::Zero());
  EXPECT_FALSE(reader.next());
}

// The binary record as docs/compensation.md lays it out, decoded here at literal offsets (not through the field
// table): the table must reproduce the version-2 format byte for byte, and the CSV header its documented text.
TEST(JointFiles, BinaryRecordHasTheDocumentedLayout) {
  EXPECT_STREQ(kJointCsvHeader,
               "t_s,theta1_rad,theta2_rad,omega1_rad_s,omega2_rad_s,alpha1_rad_s2,alpha2_rad_s2,laser,power,x_mm,y_mm,"
               "xcmd_mm,ycmd_mm,fx_n,fy_n,line");
  EXPECT_EQ(kBinaryRecordBytes, 120U);
  EXPECT_EQ(kBinaryV1RecordBytes, 112U);
  JointCommand c;
  c.t_s = 1.5;
  c.q_rad = {0.25, -0.5};
  c.qd_rad_s = {3.0, -4.0};
  c.qdd_rad_s2 = {50.0, -60.0};
  c.target_m = {0.2, 0.03};
  c.command_m = {0.2001, 0.0299};
  c.force_N = {-170.0, 85.0};
  c.power = 0.75;
  c.laser_on = true;
  c.line = 123456;
  test::TempDir dir;
  const auto path = (dir / "one.bin").string();
  auto writer = make_joint_writer(OutputFormat::binary, path, 2000.0, {"oc-gu", ""});
  writer->write(c);
  writer->finish();
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size(), 128U + 120U);
  const char* record = bytes.data() + 128;
  const auto f64 = [&](int at) {
    double v;
    std::memcpy(&v, record + at, 8);
    return v;
  };
  const double doubles[14] = {1.5, 0.25, -0.5, 3.0, -4.0, 50.0, -60.0, 0.2, 0.03, 0.2001, 0.0299, -170.0, 85.0, 0.75};
  for (int k = 0; k < 14; ++k) EXPECT_EQ(f64(8 * k), doubles[k]) << "double " << k;
  std::int32_t line;
  std::memcpy(&line, record + 112, 4);
  EXPECT_EQ(line, 123456);
  EXPECT_EQ(record[116], 1);
  EXPECT_EQ(std::string(record + 117, 3), std::string(3, '\0'));
}

// docs/compensation.md lists every field of the record, one table row each, as the field table has it; a field added to
// the table fails here until the user documentation has its row.
TEST(JointFiles, DocumentedFieldsAreTheTable) {
  std::ifstream in(std::string(STIFFPATH_SOURCE_DIR) + "/docs/compensation.md");
  const std::string doc((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(doc.empty());
  EXPECT_NE(doc.find(std::string("\n") + kJointCsvHeader + "\n"), std::string::npos) << "the header line";
  const std::size_t from = doc.find("| CSV column | CSV | binary name |");
  ASSERT_NE(from, std::string::npos) << "the record's field table";
  const std::string section = doc.substr(from, doc.find("\n\n", from) - from);
  std::size_t rows = 0;
  for (std::size_t at = section.find("\n| `"); at != std::string::npos; at = section.find("\n| `", at + 1)) ++rows;
  for (const JointField& f : kJointFields) {
    const std::string text = f.csv_text == CsvText::flag      ? "0/1"
                             : f.csv_text == CsvText::integer ? "int"
                                                              : std::to_string(f.csv_decimals);
    const std::string type = f.binary_type == BinaryType::f64 ? "f64" : f.binary_type == BinaryType::i32 ? "i32" : "u8";
    const std::string range = f.min_si == -f.max_si ? fmt::format("±{:g}", f.max_si)
                                                    : fmt::format("[{:g}, {:g}]", f.min_si, f.max_si);
    const std::string absent = f.if_absent == IfAbsent::zero ? "zero" : f.if_absent == IfAbsent::laser_bit ? "laser bit" : "refused";
    const std::string row = fmt::format("| `{}` | {} | `{}` | {} | {} | {} | {} | {} |", f.csv_name, text, f.si_name, type,
                                        f.offset_v2, f.offset_v1 < 0 ? "-" : std::to_string(f.offset_v1), range, absent);
    EXPECT_NE(section.find(row), std::string::npos) << "docs/compensation.md's field table lacks the row\n" << row;
  }
  EXPECT_EQ(rows, kJointFields.size()) << "rows of docs/compensation.md's field table";
}

// Every bounded field is refused beyond its bounds by both readers, the message naming the field in the file's unit
// (α was not range-checked in CSV, nor the line in binary files, before the readers followed the table).
TEST(JointFiles, EveryFieldIsCheckedAgainstItsBoundsInBothFormats) {
  test::TempDir dir;
  for (const JointField& f : kJointFields) {
    if (f.csv_text == CsvText::flag) continue;  // a bool cannot be written out of range (see CorruptFilesAre...)
    for (const auto format : {OutputFormat::csv, OutputFormat::binary}) {
      auto in = commands(2);
      const double beyond = f.max_si == 0.0 ? 1.0 : f.max_si * 1.5;
      if (f.member == JointMember::t_s) {
        in[0].t_s = -beyond;  // the second must follow the first in time
      } else {
        set_value(in[0], f, beyond);
      }
      const auto path = (dir / (std::string(f.csv_name) + (format == OutputFormat::csv ? ".csv" : ".bin"))).string();
      auto writer = make_joint_writer(format, path, 2000.0, {"oc-gu", ""});
      for (const auto& c : in) writer->write(c);
      writer->finish();
      JointReader reader(path);
      try {
        (void)reader.next();
        ADD_FAILURE() << f.csv_name << " = " << beyond << " was read";
      } catch (const Error& e) {
        const std::string name(format == OutputFormat::csv ? f.csv_name : f.si_name);
        EXPECT_NE(std::string(e.what()).find("RANGE: " + name + " = "), std::string::npos) << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace stiffpath::job
