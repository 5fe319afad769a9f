// Output that respects what the user named (symlink, FIFO, directory, "-"), cleanup on signals, free-space
// refusals, and readers that refuse ambiguity (duplicated CSV columns and JSON keys, numbers beyond range).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli_runner.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/output_budget.hpp"
#include "stiffpath/core/signal_cleanup.hpp"

namespace fs = std::filesystem;
using namespace stiffpath;
using stiffpath::test::TempDir;

namespace {

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(AtomicOutput, ASymlinkIsWrittenThroughToItsTargetAndKept) {
  TempDir dir;
  fs::create_directory(dir / "real");
  test::write_text(dir / "real" / "target.csv", "old\n");
  fs::create_symlink("real/target.csv", dir / "link.csv");
  core::write_file_atomically(dir / "link.csv", "new\n");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "link.csv")));
  EXPECT_EQ(read_all(dir / "real" / "target.csv"), "new\n");
  EXPECT_EQ(entries(dir / "real"), 1u);  // no temporary left beside the target
  // A dangling link creates its target.
  fs::create_symlink("real/fresh.csv", dir / "dangling.csv");
  core::write_file_atomically(dir / "dangling.csv", "x\n");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir / "dangling.csv")));
  EXPECT_EQ(read_all(dir / "real" / "fresh.csv"), "x\n");
}

TEST(AtomicOutput, AFifoIsWrittenThroughNotReplaced) {
  TempDir dir;
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = read_all(fifo); });
  core::write_file_atomically(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  struct stat info {};
  ASSERT_EQ(::stat(fifo.c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));
}

TEST(AtomicOutput, ADeviceIsWrittenThroughAndADirectoryRefused) {
  core::write_file_atomically("/dev/null", "discarded\n");
  struct stat info {};
  ASSERT_EQ(::stat("/dev/null", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
  TempDir dir;
  try {
    core::write_file_atomically(dir.path(), "x");
    FAIL() << "a directory was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(dir.path()), 0u);
}

TEST(AtomicOutput, DashIsStandardOutput) {
  testing::internal::CaptureStdout();
  core::write_file_atomically("-", "to stdout\n");
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "to stdout\n");
  EXPECT_FALSE(fs::exists("-"));
}

// A child writes half a file and is stopped by each cleanup signal: the temporary is gone and the
// exit status is 128 + signal.
TEST(AtomicOutput, ASignalRemovesTheTemporaryAndExitsWith128PlusSignal) {
  for (const int signo : {SIGINT, SIGTERM, SIGHUP}) {
    TempDir dir;
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      core::install_signal_cleanup();
      core::AtomicFile file(dir / "out.csv");
      file.stream() << "half a file" << std::flush;
      ::kill(::getpid(), signo);
      ::_exit(0);  // not reached
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "signal " << signo;
    EXPECT_EQ(WEXITSTATUS(status), 128 + signo);
    EXPECT_EQ(entries(dir.path()), 0u) << "signal " << signo;
  }
}

TEST(OutputBudget, MoreThanTheFreeSpaceIsRefusedNamingBothSizes) {
  TempDir dir;
  const double free = core::free_bytes(dir.path());
  ASSERT_GT(free, 0.0);
  EXPECT_NO_THROW(core::check_free_space(dir / "out.csv", 1000.0, "raise"));
  try {
    core::check_free_space(dir / "out.csv", free * 2 + 1e9, "try elsewhere");
    FAIL() << "not refused";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(core::human_bytes(free * 2 + 1e9)), std::string::npos) << what;
    EXPECT_NE(what.find("try elsewhere"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(core::check_free_space("-", 1e30, ""));           // stdout: nothing to check
  EXPECT_NO_THROW(core::check_free_space("/dev/null", 1e30, ""));   // a device is written through
  EXPECT_EQ(core::human_bytes(2.4e6), "2.4 MB");
}

TEST(Ambiguity, ADuplicatedCsvColumnIsRefusedAtItsSecondOccurrence) {
  std::istringstream in("a,b,a\n1,2,3\n");
  try {
    core::CsvReader csv(in, "dup.csv");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "dup.csv:1:5: DUPLICATE: column 'a' appears twice in the header (columns 1 and 3)");
  }
}

TEST(Ambiguity, ACsvNumberBeyond1e12IsRefusedWithItsColumn) {
  std::istringstream in("x_mm,y_mm\n1,2\n3,1e300\n");
  core::CsvReader csv(in, "big.csv");
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.number(1), 2.0);
  ASSERT_TRUE(csv.next());
  try {
    (void)csv.number(1);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("big.csv:3:3: column 'y_mm': RANGE: 1e300"), std::string::npos) << e.what();
  }
}

TEST(Ambiguity, ADuplicatedJsonKeyIsRefusedAtItsSecondOccurrence) {
  const std::string text = "{\n  \"a\": 1,\n  \"b\": {\"c\": 2, \"c\": 3}\n}\n";
  try {
    (void)core::parse_json(text, "dup.json");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("dup.json:3:17: DUPLICATE: key 'b.c'"), std::string::npos) << e.what();
  }
  // The same key in two different objects (array elements) is not a duplicate.
  EXPECT_NO_THROW((void)core::parse_json_document("[{\"a\": 1}, {\"a\": 2}]", "ok.json"));
}

TEST(Ambiguity, AJsonNumberBeyondDoubleRangeIsRefusedAtItsPosition) {
  try {
    (void)core::parse_json_document("{\n  \"mass_kg\":  1e400\n}\n", "big.json");
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("big.json:2:15: invalid JSON: RANGE: number 1e400"), std::string::npos) << e.what();
  }
}

}  // namespace
