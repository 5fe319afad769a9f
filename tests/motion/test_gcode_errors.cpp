// The corpus of malformed programs (tests/data/gcode_bad/): each file's first line says the error it must raise.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "stiffpath/motion/gcode_reader.hpp"

namespace stiffpath::motion {
namespace {

namespace fs = std::filesystem;

std::string first_line(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(GcodeErrors, EveryMalformedProgramRaisesItsExpectedMessage) {
  const fs::path dir = fs::path(STIFFPATH_TEST_DATA_DIR) / "gcode_bad";
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".gcode") continue;
    const std::string header = first_line(entry.path());
    const std::string prefix = "; expect: ";
    ASSERT_EQ(header.rfind(prefix, 0), 0u) << entry.path() << " lacks its '; expect: ' line";
    const std::string expected = entry.path().string() + ":" + header.substr(prefix.size());
    std::string actual = "(no error)";
    try {
      GcodeReader reader(entry.path());
      while (reader.next()) {
      }
    } catch (const Error& e) {
      actual = e.what();
    }
    EXPECT_EQ(actual, expected) << entry.path().filename();
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

TEST(GcodeErrors, MissingFileAndDirectoryAreNamed) {
  try {
    GcodeReader reader(fs::path("/nonexistent/job.gcode"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/job.gcode: cannot open G-code file");
  }
  try {
    GcodeReader reader(fs::path(STIFFPATH_TEST_DATA_DIR) / "gcode_bad");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), (fs::path(STIFFPATH_TEST_DATA_DIR) / "gcode_bad").string() + ": is a directory, not a G-code file");
  }
}

}  // namespace
}  // namespace stiffpath::motion
