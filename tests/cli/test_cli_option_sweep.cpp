// Every numeric option of every subcommand, read from its --help, given NaN, ±inf, 0, -1, 1e-300 and 1e308:
// the tool refuses it (exit 2, naming the option or a located input) or gives a finite result (exit 0).
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace stiffpath::test;

namespace {

struct Subcommand {
  const char* name;  // as typed: "kin ik"
  const char* base;  // a valid, quick command line after the name (run in a folder prepared by prepare())
};

// Quick valid invocations; the swept option is appended (CLI11 takes the last value of a repeated option).
const Subcommand subcommands[] = {
    {"kin fk", "--theta1-deg 60 --theta2-deg -30"},
    {"kin ik", "--x-mm 222 --y-mm 10"},
    {"predict", "--x-mm 222 --y-mm 10 --fx-n 100 --fy-n -50"},
    {"plan", "job.gcode"},
    {"run", "job.gcode -o out.csv"},
    {"simulate", "joints.csv"},
    {"fit", "-o model.json"},
    {"cv", ""},
    {"campaign simulate", "-o campaign.csv"},
    {"measure", "campaign.csv -o table.csv"},
    {"data check", ""},
    {"repeatability", "thesis"},
    {"render-scan", "scan.png --length-mm 10 --dpi 300"},
    {"scan", "scan.png"},
    {"mobility", ""},
};

// Options the sweep leaves out: not numbers a user tunes (seeds are any integer; --max-samples has its own test).
const std::set<std::string> skipped = {"--seed", "--help"};

// A folder with a short job, its joint file, a virtual campaign and a rendered scan, made once.
const fs::path& prepared() {
  static TempDir dir;
  static bool ready = false;
  if (!ready) {
    write_text(dir / "job.gcode", "G0 X200 Y0\nM3 S500\nG1 X210 Y5 F3000\nM5\n");
    for (const char* setup : {"run job.gcode -o joints.csv", "campaign simulate -o campaign.csv",
                              "render-scan scan.png --length-mm 10 --dpi 300"}) {
      const CliResult r = run_cli(setup, dir.path());
      if (r.exit_code != 0) ADD_FAILURE() << setup << ": " << r.err;
    }
    ready = true;
  }
  return dir.path();
}

struct NumericOption {
  std::string flag;
  int count = 1;  // "FLOAT x 2": a pair
};

// The numeric options of a subcommand's --help ("  --x-mm FLOAT REQUIRED", "  --work-offset-mm FLOAT x 2").
std::vector<NumericOption> numeric_options(const std::string& help) {
  std::vector<NumericOption> out;
  const std::regex option(R"(^\s+(?:-\w,)?(--[a-z0-9-]+)(?:,[^ ]+)?\s+(FLOAT|INT|UINT)(?:\s+x\s+(\d+))?)");
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, option)) continue;
    if (skipped.contains(m[1].str())) continue;
    out.push_back({m[1].str(), m[3].matched ? std::stoi(m[3].str()) : 1});
  }
  return out;
}

// Runs with a 60 s limit (coreutils timeout): a runaway job shows up as exit 124 instead of hanging the suite.
CliResult run_bounded(const std::string& args, const fs::path& cwd) {
  const fs::path err_path = cwd / "sweep.err";
  const std::string command =
      "cd '" + cwd.string() + "' && timeout 60 '" + std::string(STIFFPATH_CLI) + "' " + args + " 2>'" + err_path.string() + "'";
  CliResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) result.out.append(buffer, n);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_path);
  std::stringstream ss;
  ss << err.rdbuf();
  result.err = ss.str();
  return result;
}

bool has_non_finite(const std::string& text) {
  static const std::regex bad(R"((^|[^A-Za-z_])(-?nan|-?inf|infinity)([^A-Za-z_]|$))", std::regex::icase);
  return std::regex_search(text, bad);
}

class OptionSweep : public ::testing::TestWithParam<Subcommand> {};

TEST_P(OptionSweep, AbsurdNumbersAreRefusedByNameOrGiveFiniteResults) {
  const Subcommand& sub = GetParam();
  const fs::path& dir = prepared();
  const CliResult help = run_cli(std::string(sub.name) + " --help", dir);
  ASSERT_EQ(help.exit_code, 0) << help.err;
  const auto options = numeric_options(help.out);
  const CliResult base = run_cli(std::string(sub.name) + " " + sub.base, dir);
  ASSERT_EQ(base.exit_code, 0) << sub.name << " " << sub.base << ": " << base.err;
  const char* values[] = {"nan", "inf", "-inf", "0", "-1", "1e-300", "1e308"};
  for (const auto& o : options) {
    for (const char* value : values) {
      std::string arg = value;
      for (int k = 1; k < o.count; ++k) arg += std::string(",") + value;
      const std::string line = std::string(sub.name) + " " + sub.base + " " + o.flag + "=" + arg;
      SCOPED_TRACE(line);
      const CliResult r = run_bounded(line, dir);
      ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 2) << "exit " << r.exit_code << "\n" << r.err;
      if (r.exit_code == 2) {
        // The refusal names the option, or (a value the option accepts made the input absurd) a located input.
        const bool located = std::regex_search(r.err, std::regex(R"(error: [^\s:]+:\d+)"));
        EXPECT_TRUE(r.err.find(o.flag) != std::string::npos || located || r.err.find("outside") != std::string::npos)
            << r.err;
        EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
      } else {
        EXPECT_FALSE(has_non_finite(r.out)) << r.out;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EverySubcommand, OptionSweep, ::testing::ValuesIn(subcommands),
                         [](const auto& param_info) {
                           std::string name = param_info.param.name;
                           for (char& c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
