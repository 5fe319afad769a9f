// Where `run` and `plan` write: the sample cap before writing, "-o -" to standard output, symlinks kept, and a
// job stopped by a signal leaving no temporary file.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using namespace stiffpath::test;

namespace {

std::size_t count_lines(const std::string& text) { return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')); }

TEST(CliOutputs, RunRefusesAJobBeyondMaxSamplesBeforeWriting) {
  TempDir dir;
  write_text(dir / "dwell.gcode", "G0 X200 Y0\nG4 P10\n");  // 10 s at 2 kHz: 20 001 samples
  // (--smooth-ms 0: the default smoothing adds its delay, 16 samples, to the job; checked below)
  const CliResult refused = run_cli("run dwell.gcode --smooth-ms 0 --max-samples 20000 -o out.csv", dir.path());
  EXPECT_EQ(refused.exit_code, 2);
  // 20 001 samples of about 140 bytes: 2.8 MB of joint CSV.
  EXPECT_EQ(refused.err,
            "error: dwell.gcode: the job has 20001 samples (10.0 s at 2000 Hz, about 2.8 MB of joint CSV), more than the "
            "cap of 20000; raise it with --max-samples\n");
  EXPECT_FALSE(fs::exists(dir / "out.csv"));
  const CliResult allowed = run_cli("run dwell.gcode --smooth-ms 0 --max-samples 20001 -o out.bin --format bin --json", dir.path());
  ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_EQ(allowed.json()["samples"].get<int>(), 20001);
  EXPECT_EQ(fs::file_size(dir / "out.bin"), 128u + 120u * 20001u);  // binary version 2
  // The smoothing's delay counts: 8 ms = 16 more samples are over a cap of 20 001, and within 20 017.
  EXPECT_EQ(run_cli("run dwell.gcode --max-samples 20001 -o s.bin --format bin", dir.path()).exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "s.bin"));
  const CliResult smoothed = run_cli("run dwell.gcode --max-samples 20017 -o s.bin --format bin --json", dir.path());
  ASSERT_EQ(smoothed.exit_code, 0) << smoothed.err;
  EXPECT_EQ(smoothed.json()["samples"].get<int>(), 20017);
  // The default cap (20 M samples) stops a 3 h dwell before a byte is written.
  write_text(dir / "long.gcode", "G0 X200 Y0\nG4 P3000\nG4 P3000\nG4 P3000\nG4 P3000\n");
  const CliResult day = run_cli("run long.gcode -o long.csv", dir.path());
  EXPECT_EQ(day.exit_code, 2);
  EXPECT_NE(day.err.find("the job has 24000017 samples (12000.0 s at 2000 Hz"), std::string::npos) << day.err;
  EXPECT_FALSE(fs::exists(dir / "long.csv"));
}

TEST(CliOutputs, DashWritesTheJointsToStandardOutputAndTheSummaryToStandardError) {
  TempDir dir;
  write_text(dir / "job.gcode", "G0 X200 Y0\nM3 S500\nG1 X210 F600\nM5\n");
  const CliResult file = run_cli("run job.gcode -o out.csv --json", dir.path());
  ASSERT_EQ(file.exit_code, 0) << file.err;
  const CliResult piped = run_cli("run job.gcode -o - --json", dir.path());
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  std::ifstream in(dir / "out.csv", std::ios::binary);
  std::stringstream written;
  written << in.rdbuf();
  EXPECT_EQ(piped.out, written.str());  // the same bytes as the file
  EXPECT_EQ(count_lines(piped.out), file.json()["samples"].get<std::size_t>() + 2);  // the robot comment line and the header
  EXPECT_EQ(nlohmann::json::parse(piped.err)["samples"], file.json()["samples"]);
  EXPECT_FALSE(fs::exists(dir / "-"));
}

TEST(CliOutputs, ASymlinkOutputStaysALinkToTheNewFile) {
  TempDir dir;
  write_text(dir / "job.gcode", "G0 X200 Y0\nG1 X205 F600\n");
  write_text(dir / "target.csv", "old\n");
  fs::create_symlink("target.csv", dir / "link.csv");
  const CliResult r = run_cli("plan job.gcode -o link.csv", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link.csv")));
  std::ifstream in(dir / "target.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("t_s,", 0), 0u) << header;
}

// `run` on a 2000 s dwell writes for a few seconds; SIGINT, SIGTERM or SIGHUP in the middle leave no
// temporary file and the exit status is 128 + signal.
TEST(CliOutputs, ASignalDuringAJobRemovesItsTemporaryFile) {
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) {
    TempDir dir;
    write_text(dir / "long.gcode", "G0 X200 Y0\nG4 P2000\n");  // 4 M samples, about 560 MB if it finished
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      if (::chdir(dir.path().c_str()) != 0) ::_exit(99);
      ::execl(STIFFPATH_CLI, STIFFPATH_CLI, "run", "long.gcode", "-o", "out.csv", static_cast<char*>(nullptr));
      ::_exit(98);
    }
    // Wait until the temporary file exists and has grown, then stop the job.
    bool writing = false;
    for (int i = 0; i < 600 && !writing; ++i) {
      ::usleep(50'000);
      for (const auto& e : fs::directory_iterator(dir.path())) {
        std::error_code ec;
        if (e.path().filename().string().find("out.csv.tmp-") == 0 && fs::file_size(e.path(), ec) > 100'000) writing = true;
      }
    }
    EXPECT_TRUE(writing) << "the job never started writing";
    ::kill(child, signo);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "signal " << signo;
    EXPECT_EQ(WEXITSTATUS(status), 128 + signo);
    for (const auto& e : fs::directory_iterator(dir.path())) {
      EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
    }
    EXPECT_FALSE(fs::exists(dir / "out.csv"));
  }
}

}  // namespace
