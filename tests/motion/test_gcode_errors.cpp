// The corpus of malformed programs (tests/data/gcode_bad/): each file's header says the refusals it must raise.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "gcode_corpus.hpp"
#include "stiffpath/motion/gcode_reader.hpp"

namespace stiffpath::motion {
namespace {

namespace fs = std::filesystem;

TEST(GcodeErrors, EveryMalformedProgramRaisesItsExpectedMessages) {
  const auto cases = test::read_corpus(fs::path(STIFFPATH_TEST_DATA_DIR) / "gcode_bad");
  for (const auto& c : cases) {
    ASSERT_FALSE(c.expected.empty()) << c.path << " lacks its '; expect: ' lines";
    std::string expected;
    for (const auto& line : c.expected) expected += (expected.empty() ? "" : "\n") + line;
    std::string actual = "(no error)";
    try {
      GcodeReader reader(c.path, c.options);
      while (reader.next()) {
      }
    } catch (const GcodeErrors& e) {
      actual = e.what();
      EXPECT_EQ(e.errors().size() + (e.omitted() > 0 ? 1 : 0), c.expected.size()) << c.path.filename();
    }
    EXPECT_EQ(actual, expected) << c.path.filename();
  }
  EXPECT_GE(cases.size(), 50u);
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
