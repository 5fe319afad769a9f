// The thesis presets give the same results as before robots became general: joint files bit for bit (their version-1 fields), experiment, cv, kin, predict, simulate.
#include <gtest/gtest.h>

#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/core/sha256.hpp"
#include "stiffpath/job/joint_reader.hpp"

// tests/data/regression/ was written by scripts/make_thesis_regression.sh with the binary of commit
// bd69b46, the last one with the thesis-only five-bar; these tests run the same commands on this build.
// Except: the joint-file hashes of the two CAM examples (gear_outline, nameplate), whose plans changed
// when runs began to join on release (a faster plan of the same path), were rewritten then with the
// same commands, and gear_outline's again when G64 corners between uneven chords became biarcs (a
// faster plan of a path within the same P); the thesis's own examples (triangle, x and y motion) are
// still bd69b46's.
namespace stiffpath::test {
namespace {

const std::filesystem::path kReference = std::filesystem::path(STIFFPATH_TEST_DATA_DIR) / "regression";
const std::filesystem::path kExamples = std::filesystem::path(STIFFPATH_SOURCE_DIR) / "examples";

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Each variant of scripts/make_thesis_regression.sh, which ran a build whose default was the thesis's method: here
// named as such (--thesis; for the physical model, its quasi-static step without filters). --mechanism is an
// alias of --robot.
std::string flags_of(const std::string& tag) {
  if (tag == "bin") return "--thesis --format bin";
  if (tag == "csv") return "--thesis --format csv";
  if (tag == "sc-gl" || tag == "oc-gl") return "--thesis --format bin --robot " + tag;
  if (tag == "physical") return "--compensation quasi-static --smooth-ms 0 --format bin --model thesis-oc-physical";
  if (tag == "numeric") return "--thesis --format bin --accel-source numeric";
  if (tag == "gain") return "--thesis --format bin --gain 0.8";
  if (tag == "plain") return "--thesis --format bin --no-compensation";
  ADD_FAILURE() << "unknown variant " << tag;
  return "";
}

// The bytes a version-1 binary joint file (64-byte header, 112-byte records) held for the same content:
// version 2 adds the robot's geometry to the header and the power to each record, after the old fields.
std::string as_version_one(const std::string& bytes) {
  std::string v1 = bytes.substr(0, 64);
  const std::uint32_t version = 1, record = 112;
  std::memcpy(v1.data() + 8, &version, 4);
  std::memcpy(v1.data() + 12, &record, 4);
  for (std::size_t at = 128; at + 120 <= bytes.size(); at += 120) {
    v1 += bytes.substr(at, 13 * 8);        // t … Fy
    v1 += bytes.substr(at + 14 * 8, 8);    // line, laser, padding (after the power)
  }
  return v1;
}

std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Every number of the CSV is the binary file's value correctly rounded (printf, ties to even) to the
// column's decimals: the CSV says what the (bit-identical) binary says.
void expect_csv_matches_binary(const std::filesystem::path& csv, const std::filesystem::path& bin) {
  job::JointReader binary(bin.string());
  std::ifstream in(csv);
  std::string row;
  std::getline(in, row);  // the robot comment
  std::getline(in, row);  // the header
  std::size_t k = 0;
  const auto fixed = [](double v, int d) {
    char text[400];
    std::snprintf(text, sizeof text, "%.*f", d, v);
    const std::string out(text);
    return out.find_first_not_of("-0.") == std::string::npos && out[0] == '-' ? out.substr(1) : out;
  };
  while (const auto c = binary.next()) {
    ASSERT_TRUE(std::getline(in, row)) << k;
    const std::string expected =
        fixed(c->t_s, 6) + "," + fixed(c->q_rad.x(), 9) + "," + fixed(c->q_rad.y(), 9) + "," + fixed(c->qd_rad_s.x(), 9) +
        "," + fixed(c->qd_rad_s.y(), 9) + "," + fixed(c->qdd_rad_s2.x(), 6) + "," + fixed(c->qdd_rad_s2.y(), 6) + "," +
        (c->laser_on ? "1" : "0") + "," + fixed(c->power, 6) + "," + fixed(c->target_m.x() * 1e3, 6) + "," +
        fixed(c->target_m.y() * 1e3, 6) + "," + fixed(c->command_m.x() * 1e3, 6) + "," +
        fixed(c->command_m.y() * 1e3, 6) + "," + fixed(c->force_N.x(), 4) + "," + fixed(c->force_N.y(), 4) + "," +
        std::to_string(c->line);
    ASSERT_EQ(row, expected) << csv << " row " << k;
    ++k;
  }
  EXPECT_FALSE(std::getline(in, row)) << csv << ": more rows than the binary file";
}

// Binary files: the version-1 fields are bit for bit those of the reference; CSV files (whose digits the
// correctly rounded formatter may change in the last place) say exactly what the binary file says.
TEST(CliThesisRegression, JointFilesOfEveryExampleAreBitIdentical) {
  std::ifstream in(kReference / "joint_hashes.txt");
  TempDir dir;
  int checked = 0;
  for (std::string name, tag, hash; in >> name >> tag >> hash;) {
    const auto job = kExamples / (name + ".gcode");
    const std::string run = "run '" + job.string() + "' --accel 5g ";
    const CliResult r = run_cli(run + (tag == "csv" ? flags_of("bin") : flags_of(tag)) + " -o j", dir.path());
    ASSERT_EQ(r.exit_code, 0) << name << ' ' << tag << ": " << r.err;
    if (tag == "csv") {  // the same job as tag "bin", whose binary file the hash there pins
      ASSERT_EQ(run_cli(run + flags_of(tag) + " -o j.csv", dir.path()).exit_code, 0);
      expect_csv_matches_binary(dir / "j.csv", dir / "j");
    } else {
      EXPECT_EQ(core::sha256_hex(as_version_one(read_bytes(dir / "j"))), hash) << name << ' ' << tag;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 5 * 8);
}

TEST(CliThesisRegression, TheExperimentMatrixIsUnchanged) {
  TempDir dir;
  // The twin as it was: C_true physical, servos that do not feel the load, the CG at G, the thesis's method only.
  const CliResult r = run_cli("experiment -o exp --no-plots --truth physical --servo ideal --no-cg-lever "
                              "--variants thesis",
                              dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The first two columns were renamed (mechanism, build → robot, rows); the values are the same. Two
  // last columns are new: variant (the compensation: "thesis" when compensated, empty without) and source
  // ("simulated" on every row). The mark metrics (length … CO) were re-recorded when they were made the
  // scan's, along the mark (arc-length samples, each stroke cut into sides at its command's corners,
  // AT_p per side): the twin's own columns (duration, residual vibration, peak deflection) are the
  // original reference's, unchanged.
  const auto read = [](const std::filesystem::path& path) {
    std::ifstream file(path);
    std::vector<std::string> rows;
    for (std::string line; std::getline(file, line);) rows.push_back(line);
    return rows;
  };
  auto now = read(dir / "exp" / "results.csv");
  const auto before = read(kReference / "experiment_results.csv");
  ASSERT_EQ(now.size(), 121U);
  ASSERT_EQ(now.size(), before.size());
  std::vector<std::string> tails(now.size());
  for (std::size_t k = 0; k < now.size(); ++k) {
    const auto cut = now[k].rfind(',', now[k].rfind(',') - 1);  // before "variant,source"
    tails[k] = now[k].substr(cut + 1);
    now[k] = now[k].substr(0, cut);
  }
  EXPECT_EQ(tails[0], "variant,source");
  EXPECT_EQ(now[0].substr(now[0].find(",cg,")), before[0].substr(before[0].find(",cg,")));
  for (std::size_t k = 1; k < now.size(); ++k) {
    EXPECT_EQ(now[k], before[k]) << k;
    std::stringstream cells(now[k]);
    std::string cell;
    for (int c = 0; c < 4; ++c) std::getline(cells, cell, ',');
    const bool compensated = cell == "1";  // the 4th cell, compensated
    EXPECT_EQ(tails[k], compensated ? "thesis,simulated" : ",simulated") << k;
  }
}

TEST(CliThesisRegression, CrossValidationKinematicsAndPredictionsAreUnchanged) {
  for (const std::string build : {"oc", "sc"}) {
    const CliResult r = run_cli("cv --robot " + build + "-gu --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto now = r.json(), before = read_json(kReference / ("cv_" + build + ".json"));
    // The reference's methods unchanged, in their order; physical-spline came after it was written.
    ASSERT_EQ(now["methods"].size(), before["methods"].size() + 1);
    EXPECT_EQ(now["methods"].back()["method"], "physical-spline");
    for (std::size_t m = 0; m < before["methods"].size(); ++m) {
      const auto& a = now["methods"][m];
      const auto& b = before["methods"][m];
      EXPECT_EQ(a["method"], b["method"]);
      for (const char* key : {"mean_error_um", "max_error_um", "interior_mean_error_um", "predicted_points", "points"}) {
        EXPECT_EQ(a[key], b[key]) << build << ' ' << b["method"] << ' ' << key;
      }
    }
  }
  const CliResult grid = run_cli("kin grid --json");
  ASSERT_EQ(grid.exit_code, 0) << grid.err;
  EXPECT_EQ(grid.json()["points"], read_json(kReference / "kin_grid.json")["points"]);
  for (const std::string model : {"thesis-oc", "thesis-sc-physical"}) {
    const CliResult p = run_cli("predict --model " + model + " --x-mm 240.5 --y-mm -20.25 --fx-n 180 --fy-n -95 --json");
    ASSERT_EQ(p.exit_code, 0) << p.err;
    const auto now = p.json();
    // Every value of the reference unchanged; keys added since (the prediction's uncertainty) are not the thesis's.
    const auto reference = read_json(kReference / ("predict_" + model + ".json"));
    for (const auto& [key, value] : reference.items()) {
      ASSERT_TRUE(now.contains(key)) << model << ' ' << key;
      EXPECT_EQ(now[key], value) << model << ' ' << key;
    }
  }
}

// The twin as the reference files knew it (C_true physical, unloaded servos, the CG at G).
const std::string kOldTwin = "--truth physical --servo ideal --no-cg-lever";

TEST(CliThesisRegression, TheTwinMeasuresTheSameMarks) {
  TempDir dir;
  const auto example = [](const char* name) { return "'" + (kExamples / name).string() + "'"; };
  ASSERT_EQ(run_cli("run " + example("y_motion.gcode") + " --accel 5g --thesis --format bin -o y.bin", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + example("triangle.gcode") + " --accel 3g --smooth-ms 0 --format bin --robot sc-gu --no-compensation -o t.bin",
                    dir.path())
                .exit_code,
            0);
  const std::vector<std::pair<std::string, std::string>> runs{
      {"simulate y.bin --json " + kOldTwin, "simulate_y_oc-gu.json"},
      {"simulate t.bin --sides 3 --robot sc-gu --json " + kOldTwin, "simulate_triangle_sc-gu_plain.json"}};
  for (const auto& [args, file] : runs) {
    const CliResult r = run_cli(args, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto now = r.json(), before = read_json(kReference / file);
    // Every metric of the reference is unchanged (the mark metrics as re-recorded when they were made
    // the scan's, along the mark; duration, peaks and marked points as first recorded); per-stroke
    // metrics were added since.
    for (const auto& [key, value] : before.items()) {
      if (key != "mechanism") {
        EXPECT_EQ(now[key], value) << file << ' ' << key;
      }
    }
    EXPECT_EQ(now["strokes"], 1) << file;
  }
}

}  // namespace
}  // namespace stiffpath::test
