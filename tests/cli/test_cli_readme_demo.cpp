// The README's demo line quotes what the demo prints: the same commands, the same numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

const std::string kSource = STIFFPATH_SOURCE_DIR;

TEST(ReadmeDemo, TheQuotedLengthErrorAndAreaAreWhatTheDemoPrints) {
  std::ifstream readme(kSource + "/README.md");
  std::stringstream text;
  text << readme.rdbuf();
  std::smatch m;
  const std::string all = text.str();
  ASSERT_TRUE(std::regex_search(all, m, std::regex(R"(length error ([0-9.]+) -> ([0-9.]+) mm, area ([0-9.]+) -> ([0-9.]+) mm\^2)")))
      << "README.md no longer quotes the demo's length error and area";
  const double quoted[4] = {std::stod(m[1]), std::stod(m[2]), std::stod(m[3]), std::stod(m[4])};
  // As scripts/demo.sh runs them: the triangle at 5 g without and with compensation, both on the twin.
  TempDir dir;
  const std::string job = kSource + "/examples/triangle.gcode";
  ASSERT_EQ(run_cli("run " + job + " --accel 5g --no-compensation -o plain.csv", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("run " + job + " --accel 5g -o compensated.csv", dir.path()).exit_code, 0);
  const CliResult plain = run_cli("simulate plain.csv --sides 3 --json", dir.path());
  const CliResult compensated = run_cli("simulate compensated.csv --sides 3 --json", dir.path());
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(compensated.exit_code, 0) << compensated.err;
  // The README rounds: lengths to the µm it prints, areas to 0.1 mm².
  EXPECT_NEAR(std::abs(plain.json()["length_error_mm"].get<double>()), quoted[0], 0.0005);
  EXPECT_NEAR(std::abs(compensated.json()["length_error_mm"].get<double>()), quoted[1], 0.0005);
  EXPECT_NEAR(plain.json()["deviation_area_mm2"].get<double>(), quoted[2], 0.05);
  EXPECT_NEAR(compensated.json()["deviation_area_mm2"].get<double>(), quoted[3], 0.05);
}

}  // namespace
}  // namespace stiffpath::test
