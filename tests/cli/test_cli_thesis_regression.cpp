// The thesis presets give the same results as before robots became general: joint files bit for bit, experiment, cv, kin, predict, simulate.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/core/sha256.hpp"

// tests/data/regression/ was written by scripts/make_thesis_regression.sh with the binary of commit
// bd69b46, the last one with the thesis-only five-bar; these tests run the same commands on this build.
namespace stiffpath::test {
namespace {

const std::filesystem::path kReference = std::filesystem::path(STIFFPATH_TEST_DATA_DIR) / "regression";
const std::filesystem::path kExamples = std::filesystem::path(STIFFPATH_SOURCE_DIR) / "examples";

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Each variant of scripts/make_thesis_regression.sh (the flags are the same; --mechanism is an alias of --robot).
std::string flags_of(const std::string& tag) {
  if (tag == "bin") return "--format bin";
  if (tag == "csv") return "--format csv";
  if (tag == "sc-gl" || tag == "oc-gl") return "--format bin --robot " + tag;
  if (tag == "physical") return "--format bin --model thesis-oc-physical";
  if (tag == "numeric") return "--format bin --accel-source numeric";
  if (tag == "gain") return "--format bin --gain 0.8";
  if (tag == "plain") return "--format bin --no-compensation";
  ADD_FAILURE() << "unknown variant " << tag;
  return "";
}

TEST(CliThesisRegression, JointFilesOfEveryExampleAreBitIdentical) {
  std::ifstream in(kReference / "joint_hashes.txt");
  TempDir dir;
  int checked = 0;
  for (std::string name, tag, hash; in >> name >> tag >> hash;) {
    const auto job = kExamples / (name + ".gcode");
    const CliResult r = run_cli("run '" + job.string() + "' --accel 5g " + flags_of(tag) + " -o j", dir.path());
    ASSERT_EQ(r.exit_code, 0) << name << ' ' << tag << ": " << r.err;
    EXPECT_EQ(core::sha256_file_hex((dir / "j").string()), hash) << name << ' ' << tag;
    ++checked;
  }
  EXPECT_EQ(checked, 5 * 8);
}

TEST(CliThesisRegression, TheExperimentMatrixIsUnchanged) {
  TempDir dir;
  const CliResult r = run_cli("experiment -o exp --no-plots", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The first two columns were renamed (mechanism, build → robot, rows); the values are the same.
  const auto read = [](const std::filesystem::path& path) {
    std::ifstream file(path);
    std::vector<std::string> rows;
    for (std::string line; std::getline(file, line);) rows.push_back(line);
    return rows;
  };
  const auto now = read(dir / "exp" / "results.csv"), before = read(kReference / "experiment_results.csv");
  ASSERT_EQ(now.size(), 121U);
  ASSERT_EQ(now.size(), before.size());
  // A last column, source, was added later: "simulated" on every row.
  EXPECT_EQ(now[0].substr(now[0].find(",cg,")), before[0].substr(before[0].find(",cg,")) + ",source");
  for (std::size_t k = 1; k < now.size(); ++k) EXPECT_EQ(now[k], before[k] + ",simulated") << k;
}

TEST(CliThesisRegression, CrossValidationKinematicsAndPredictionsAreUnchanged) {
  for (const std::string build : {"oc", "sc"}) {
    const CliResult r = run_cli("cv --robot " + build + "-gu --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto now = r.json(), before = read_json(kReference / ("cv_" + build + ".json"));
    ASSERT_EQ(now["methods"].size(), before["methods"].size());
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
    auto now = p.json();
    now.erase("robot");
    EXPECT_EQ(now, read_json(kReference / ("predict_" + model + ".json"))) << model;
  }
}

TEST(CliThesisRegression, TheTwinMeasuresTheSameMarks) {
  TempDir dir;
  const auto example = [](const char* name) { return "'" + (kExamples / name).string() + "'"; };
  ASSERT_EQ(run_cli("run " + example("y_motion.gcode") + " --accel 5g --format bin -o y.bin", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + example("triangle.gcode") + " --accel 3g --format bin --robot sc-gu --no-compensation -o t.bin",
                    dir.path())
                .exit_code,
            0);
  const std::vector<std::pair<std::string, std::string>> runs{
      {"simulate y.bin --json", "simulate_y_oc-gu.json"},
      {"simulate t.bin --sides 3 --robot sc-gu --json", "simulate_triangle_sc-gu_plain.json"}};
  for (const auto& [args, file] : runs) {
    const CliResult r = run_cli(args, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto now = r.json(), before = read_json(kReference / file);
    now.erase("robot");
    before.erase("mechanism");
    EXPECT_EQ(now, before) << file;
  }
}

}  // namespace
}  // namespace stiffpath::test
