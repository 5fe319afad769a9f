// Round trips of the joint-file writers and reader (CSV, binary), fixed-point formatting, and corrupt files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "cli_runner.hpp"
#include "stiffpath/job/joint_reader.hpp"
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

TEST(AppendFixed, FormatsLikePrintf) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-400.0, 400.0);
  for (int i = 0; i < 20000; ++i) {
    const double v = u(rng);
    for (int d : {0, 4, 6, 9}) {
      std::string ours;
      append_fixed(ours, v, d);
      char ref[64];
      std::snprintf(ref, sizeof ref, "%.*f", d, v);
      // printf rounds the exact binary value, we round v·10^d: they may differ in the last digit only.
      ASSERT_NEAR(std::stod(ours), std::stod(ref), std::pow(10.0, -d) * 1.0001) << v << " " << d;
    }
  }
  std::string s;
  append_fixed(s, -0.0000000001, 6);
  EXPECT_EQ(s, "0.000000");
  s.clear();
  append_fixed(s, -1.5, 0);
  EXPECT_EQ(s, "-2");
  s.clear();
  append_fixed(s, 0.0005, 6);
  EXPECT_EQ(s, "0.000500");
}

TEST(JointFiles, BinaryRoundTripIsExact) {
  test::TempDir dir;
  const auto path = (dir / "j.bin").string();
  const auto in = commands(5000);
  auto writer = make_joint_writer(OutputFormat::binary, path, 2000.0, "oc-gu");
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
  auto writer = make_joint_writer(OutputFormat::csv, path, 2000.0, "oc-gu");
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
    auto writer = make_joint_writer(OutputFormat::csv, (dir / "j.csv").string(), 2000.0, "oc-gu");
    for (const auto& c : commands(10)) writer->write(c);
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(JointFiles, CorruptFilesAreReportedWithTheirPlace) {
  test::TempDir dir;
  const auto path = (dir / "j.bin").string();
  auto writer = make_joint_writer(OutputFormat::binary, path, 2000.0, "oc-gu");
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
  test::write_text(dir / "bad.csv", std::string(kJointCsvHeader) + "\n0,0.1,0.2,0,0,2,200,0,200,0,0,0,5\n");
  JointReader csv((dir / "bad.csv").string());
  try {
    (void)csv.next();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("column 'laser': must be 0 or 1, got 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stiffpath::job
