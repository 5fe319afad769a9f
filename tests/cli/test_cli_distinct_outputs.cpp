// An output never replaces an input of its command (every command's input/output pairs, by path, symbolic and hard
// link), directory outputs appear whole or not at all (a full disk, Ctrl-C while gnuplot draws), and standard output
// failures and empty output names are refused.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "stiffpath/report/gnuplot.hpp"

namespace fs = std::filesystem;
using namespace stiffpath::test;

namespace {

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool has_temporary(const fs::path& dir) {
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().filename().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

// The inputs every pair below draws from, made by the CLI itself in `dir`.
void make_inputs(const fs::path& dir) {
  write_text(dir / "job.gcode", "G0 X200 Y0\nM3 S500\nG1 X210 F600\nM5\n");
  std::string robot = bytes_of(fs::path(STIFFPATH_TEST_DATA_DIR) / ".." / ".." / "data" / "robots" / "oc-gu.json");
  robot = std::regex_replace(robot, std::regex("\"\\.\\./thesis/"), "\"builtin:thesis/");
  write_text(dir / "r.json", robot);
  ASSERT_EQ(run_cli("fit --robot oc-gu --method bilinear -o m.json", dir).exit_code, 0);
  ASSERT_EQ(run_cli("campaign simulate --robot oc-gu -o c.csv --truth-output t.csv", dir).exit_code, 0);
  ASSERT_EQ(run_cli("run job.gcode -o j.csv", dir).exit_code, 0);
  ASSERT_EQ(run_cli("render-scan img.png --length-mm 10 --dpi 300", dir).exit_code, 0);
  write_text(dir / "p.csv", "x_mm,y_mm\n10,10\n20,10\n");
}

// One input/output pair of one command: `command` with {in} the input's name and {out} the output's name.
struct Pair {
  const char* command;
  const char* input;   // the file that must survive
  const char* option;  // the output option the message names
};

const Pair pairs[] = {
    {"run {in} -o {out}", "job.gcode", "-o"},
    {"run job.gcode --robot {in} -o {out}", "r.json", "-o"},
    {"run job.gcode --model {in} -o {out}", "m.json", "-o"},
    {"plan {in} -o {out}", "job.gcode", "-o"},
    {"plan job.gcode --robot {in} -o {out}", "r.json", "-o"},
    {"measure {in} -o {out}", "c.csv", "-o"},
    {"measure c.csv --robot {in} -o {out}", "r.json", "-o"},
    {"fit --robot {in} -o {out}", "r.json", "-o"},
    {"fit {in} -o {out}", "t.csv", "-o"},
    {"campaign simulate --truth {in} -o {out}", "t.csv", "-o"},
    {"campaign simulate --truth t.csv -o x.csv --truth-output {out} --robot {in}", "r.json", "--truth-output"},
    {"simulate {in} --marks-csv {out}", "j.csv", "--marks-csv"},
    {"scan {in} --overlay {out}", "img.png", "--overlay"},
    {"render-scan {out} --path-csv {in}", "p.csv", "output"},
    {"render-scan o.png --path-csv {in} --truth {out}", "p.csv", "--truth"},
    {"campaign plan --robot {in} -o {out}", "r.json", "-o"},
    {"geometry plan --robot {in} -o {out}", "r.json", "-o"},
    {"geometry fit {in} -o {out}", "c.csv", "-o"},
    {"geometry simulate --truth {in} --poses c.csv -o {out}", "r.json", "-o"},
    {"calibrate fit plate.json scan.png --joints {in} -o {out}", "c.csv", "-o"},
};

std::string command_for(std::string text, const std::string& in, const std::string& out) {
  text = std::regex_replace(text, std::regex("\\{in\\}"), in);
  return std::regex_replace(text, std::regex("\\{out\\}"), out);
}

TEST(DistinctOutputs, NoCommandReplacesItsInputByPathSymbolicOrHardLink) {
  TempDir dir;
  make_inputs(dir.path());
  for (const Pair& pair : pairs) {
    for (const std::string how : {"path", "symlink", "hardlink"}) {
      SCOPED_TRACE(std::string(pair.command) + " (" + how + ")");
      const std::string before = bytes_of(dir / pair.input);
      ASSERT_FALSE(before.empty());
      std::string out = pair.input;
      if (how == "symlink") {
        out = "link";
        fs::remove(dir / out);
        fs::create_symlink(pair.input, dir / out);
      } else if (how == "hardlink") {
        out = "hard";
        fs::remove(dir / out);
        fs::create_hard_link(dir / pair.input, dir / out);
      }
      const CliResult r = run_cli(command_for(pair.command, pair.input, out), dir.path());
      EXPECT_EQ(r.exit_code, 2) << r.err;
      // Both names, the output's option and the input's, are in the refusal.
      EXPECT_NE(r.err.find(std::string(pair.option) + " " + out + " is the same file as the input"), std::string::npos)
          << r.err;
      EXPECT_NE(r.err.find(pair.input), std::string::npos) << r.err;
      EXPECT_EQ(bytes_of(dir / pair.input), before);
      if (how == "symlink") {
        EXPECT_TRUE(fs::is_symlink(dir / out));
      }
      EXPECT_FALSE(has_temporary(dir.path()));
    }
  }
}

TEST(DistinctOutputs, TwoOutputsOfOneCommandAreNeverOneFile) {
  TempDir dir;
  make_inputs(dir.path());
  const CliResult r = run_cli("campaign simulate --robot oc-gu -o x.csv --truth-output x.csv", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--truth-output x.csv is the same file as the output -o x.csv"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.csv"));
  // Nor through a link to a file that does not exist yet, nor both on standard output.
  fs::create_symlink("y.csv", dir / "ylink");
  EXPECT_EQ(run_cli("campaign simulate --robot oc-gu -o y.csv --truth-output ylink", dir.path()).exit_code, 2);
  EXPECT_EQ(run_cli("campaign simulate --robot oc-gu -o - --truth-output -", dir.path()).exit_code, 2);
  // Distinct files are fine, and a device written twice is not replaced.
  EXPECT_EQ(run_cli("campaign simulate --robot oc-gu -o /dev/null --truth-output /dev/null", dir.path()).exit_code, 0);
  EXPECT_EQ(run_cli("simulate j.csv --marks-csv /dev/null", dir.path()).exit_code, 0);
}

// Every (sub)command whose --help offers an output file or directory is in the table above or in the directory
// tests below, so that a new command cannot skip the check unnoticed.
TEST(DistinctOutputs, EveryCommandWithAnOutputIsWalked) {
  std::set<std::string> walked;
  for (const Pair& p : pairs) {
    const std::string c = p.command;
    walked.insert(c.substr(0, c.find(' ', c.rfind("campaign", 0) == 0 ? 9 : 0)));
  }
  for (const char* d : {"experiment", "report", "plot"}) walked.insert(d);  // directory outputs: tests below
  // Folders that must be new (linuxcnc config) or hold only the command's own files (calibrate plate).
  for (const char* d : {"linuxcnc config", "calibrate plate"}) walked.insert(d);
  const CliResult top = run_cli("--help");
  std::istringstream lines(top.out);
  bool in_subcommands = false;
  std::vector<std::string> commands;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_subcommands = true;
      continue;
    }
    std::smatch m;
    if (in_subcommands && std::regex_search(line, m, std::regex("^  ([a-z-]+)"))) commands.push_back(m[1]);
  }
  ASSERT_GE(commands.size(), 15u);
  for (const auto& command : commands) {
    std::vector<std::string> names{command};
    const CliResult help = run_cli(command + " --help");
    std::istringstream sub(help.out);
    bool subs = false;
    for (std::string line; std::getline(sub, line);) {
      if (line.rfind("Subcommands:", 0) == 0) subs = true;
      std::smatch m;
      if (subs && std::regex_search(line, m, std::regex("^  ([a-z-]+) "))) names.push_back(command + " " + m[1].str());
    }
    for (const auto& name : names) {
      const std::string text = run_cli(name + " --help").out;
      const bool writes = std::regex_search(text, std::regex("(-o,--output|--overlay|--marks-csv|--truth-output|"
                                                             "Image to write)"));
      const std::string top_name = name.substr(0, name.find(' '));
      if (writes) {
        EXPECT_TRUE(walked.contains(name) || walked.contains(top_name)) << name << " writes a file but is not walked";
      }
    }
  }
}

TEST(DistinctOutputs, AnEmptyOutputNameAndAFailingStandardOutputAreRefused) {
  TempDir dir;
  write_text(dir / "job.gcode", "G0 X200 Y0\nG1 X210 F600\n");
  for (const char* command : {"run job.gcode -o ''", "plan job.gcode -o ''", "fit -o ''", "experiment -o ''"}) {
    const CliResult r = run_cli(command, dir.path());
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_NE(r.err.find("an empty name names no file"), std::string::npos) << r.err;
  }
  // What was printed could not be written: exit 2 with a message, not success.
  const CliResult full = run_cli("plan job.gcode --json >/dev/full", dir.path());
  EXPECT_EQ(full.exit_code, 2);
  EXPECT_NE(full.err.find("error: standard output: write failed (No space left on device)"), std::string::npos)
      << full.err;
  EXPECT_EQ(run_cli("plan job.gcode --json >/dev/null", dir.path()).exit_code, 0);
}

// A small measured results table (figs. 4.9a/b: the y motion, with and without compensation).
void write_results(const fs::path& path) {
  write_text(path, "robot,motion,compensated,acceleration_g,length_mm,deviation_area_mm2,source\n"
                   "oc,y,0,1,149.9,0.5,measured\noc,y,1,1,150.0,0.2,measured\n"
                   "oc,y,0,3,149.5,0.9,measured\noc,y,1,3,149.9,0.3,measured\n");
}

// A results table whose name is a data file that `plot results` writes, inside the output directory: the figures
// are drawn, then refused before a file is moved in, and the table survives.
TEST(DirectoryOutputs, AnInputInsideTheDirectoryIsNeverReplaced) {
  if (!stiffpath::report::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  TempDir dir;
  fs::create_directories(dir / "plots");
  const fs::path table = dir / "plots" / "fig_4_9a_y_length.tsv";
  write_results(table);
  const std::string before = bytes_of(table);
  const CliResult r = run_cli("plot results plots/fig_4_9a_y_length.tsv -o plots", dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("this output is the same file as the input table plots/fig_4_9a_y_length.tsv"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(bytes_of(table), before);
  EXPECT_FALSE(fs::exists(dir / "plots" / "fig_4_9a_y_length.svg"));  // nothing moved in
  EXPECT_FALSE(has_temporary(dir.path()));
}

// Into an existing directory the new figures are added, other files stay; a new directory appears whole.
TEST(DirectoryOutputs, FiguresAreAddedToAnExistingDirectoryOrAppearInANewOneWhole) {
  if (!stiffpath::report::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  TempDir dir;
  const fs::path results = dir / "results.csv";
  write_results(results);
  fs::create_directories(dir / "old");
  write_text(dir / "old" / "mine.txt", "kept");
  ASSERT_EQ(run_cli("plot results '" + results.string() + "' -o old", dir.path()).exit_code, 0);
  EXPECT_EQ(bytes_of(dir / "old" / "mine.txt"), "kept");
  EXPECT_TRUE(fs::exists(dir / "old" / "fig_4_9a_y_length.svg"));
  ASSERT_EQ(run_cli("plot results '" + results.string() + "' -o new/deeper", dir.path()).exit_code, 0);
  EXPECT_TRUE(fs::exists(dir / "new" / "deeper" / "fig_4_9a_y_length.png"));
  EXPECT_FALSE(has_temporary(dir.path()));
}

// Runs a shell command in `cwd` (not through run_cli, which puts the binary first); its exit code and stderr.
int shell(const std::string& command, const fs::path& cwd, std::string& err) {
  const fs::path err_file = fs::temp_directory_path() / ("stiffpath_shell_err_" + std::to_string(::getpid()));
  const std::string full = "cd '" + cwd.string() + "' && " + command + " >/dev/null 2>'" + err_file.string() + "'";
  const int status = std::system(full.c_str());
  err = bytes_of(err_file);
  fs::remove(err_file);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A full disk while gnuplot draws (a file-size limit: writes beyond it fail as on a full disk, SIGXFSZ ignored as a
// shell does): exit 2 and no half-filled directory, new or existing.
TEST(DirectoryOutputs, AFullDiskLeavesNothingHalfFilled) {
  if (!stiffpath::report::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed";
  TempDir dir;
  const fs::path results = dir / "results.csv";
  write_results(results);
  fs::create_directories(dir / "old");
  write_text(dir / "old" / "mine.txt", "kept");
  for (const std::string out : {"fresh", "old"}) {
    SCOPED_TRACE(out);
    // 16 blocks of 512 bytes: the data files and scripts fit, the figures do not.
    std::string err;
    const int code = shell("sh -c \"trap '' XFSZ; ulimit -f 16; exec '" + std::string(STIFFPATH_CLI) + "' plot results '" +
                               results.string() + "' -o " + out + "\"",
                           dir.path(), err);
    EXPECT_EQ(code, 2) << err;
    EXPECT_NE(err.find("disk full?"), std::string::npos) << err;
  }
  EXPECT_FALSE(fs::exists(dir / "fresh"));
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir / "old")) left.push_back(e.path().filename().string());
  EXPECT_EQ(left, std::vector<std::string>{"mine.txt"});
  EXPECT_FALSE(has_temporary(dir.path()));
}

// Ctrl-C while gnuplot draws (a stand-in that waits, so the signal lands while it runs): stiffpath stops it, removes
// the staging directory and exits 130, rather than ignoring the signal as std::system does.
TEST(DirectoryOutputs, InterruptedWhilePlottingStopsGnuplotAndLeavesNothing) {
  TempDir dir;
  fs::create_directories(dir / "bin");
  const fs::path pid_file = dir / "gnuplot.pid";
  write_text(dir / "bin" / "gnuplot", "#!/bin/sh\necho $$ > '" + pid_file.string() + "'\nexec sleep 60\n");
  fs::permissions(dir / "bin" / "gnuplot", fs::perms::owner_all);
  const fs::path results = dir / "results.csv";
  write_results(results);
  for (const int signo : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signo);
    fs::remove(pid_file);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      if (::chdir(dir.path().c_str()) != 0) ::_exit(99);
      const std::string path = (dir / "bin").string() + ":" + std::getenv("PATH");
      ::setenv("PATH", path.c_str(), 1);
      ::execl(STIFFPATH_CLI, STIFFPATH_CLI, "plot", "results", results.c_str(), "-o", "figs", static_cast<char*>(nullptr));
      ::_exit(98);
    }
    for (int i = 0; i < 400 && !fs::exists(pid_file); ++i) ::usleep(50'000);
    ASSERT_TRUE(fs::exists(pid_file)) << "gnuplot never started";
    ::usleep(100'000);
    const pid_t gnuplot = std::stoi(bytes_of(pid_file));
    ::kill(child, signo);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 128 + signo);
    EXPECT_NE(::kill(gnuplot, 0), 0) << "gnuplot still runs";
    EXPECT_FALSE(fs::exists(dir / "figs"));
    EXPECT_FALSE(has_temporary(dir.path()));
  }
}

}  // namespace
