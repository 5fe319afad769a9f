// The malformed-input corpus (tests/data/bad/<reader>/, expect.txt per reader) driven through the CLI: each file is
// refused with exit 2 and a message naming its location and offending value, and no output file appears.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "gcode_corpus.hpp"
#include "stiffpath/vision/io/resolution.hpp"

namespace fs = std::filesystem;
using namespace stiffpath::test;

namespace {

const fs::path bad_dir = fs::path(STIFFPATH_TEST_DATA_DIR) / "bad";

struct Reader {
  const char* folder;
  const char* command;  // {} is the corpus file; the output, if any, is out.*
  const char* output;   // the file that must not appear ("" for none)
};

const Reader readers[] = {
    {"displacement_table", "fit '{}' -o out.json", "out.json"},
    {"campaign", "measure '{}' -o out.csv", "out.csv"},
    {"repeatability", "repeatability '{}' --json", ""},
    {"robot", "plan job.gcode --robot '{}' -o out.csv", "out.csv"},
    {"model", "run job.gcode --model '{}' -o out.csv", "out.csv"},
    {"joints", "simulate '{}' --marks-csv out.csv", "out.csv"},
    {"image", "scan '{}' --overlay out.png", "out.png"},
    {"plate", "render-scan out.png --plate '{}' --dpi 100", "out.png"},
    {"mark_csv", "render-scan out.png --path-csv '{}'", "out.png"},
    // (the plate is read before the scan and the joint file, which need not exist)
    {"calibration_plate", "calibrate fit '{}' scan.png --joints joints.bin --robot oc-gu -o out.json", "out.json"},
};

struct Case {
  std::string file, where, value;
};

std::vector<Case> read_expectations(const fs::path& folder) {
  std::vector<Case> out;
  std::ifstream in(folder / "expect.txt");
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Case c;
    std::getline(fields, c.file, '\t');
    std::getline(fields, c.where, '\t');
    std::getline(fields, c.value, '\t');
    out.push_back(c);
  }
  return out;
}

std::string replace(std::string text, const std::string& with) {
  return text.replace(text.find("{}"), 2, with);
}

class BadInputs : public ::testing::TestWithParam<Reader> {};

TEST_P(BadInputs, EveryFileIsRefusedAtItsLocationNamingTheValueAndWritesNothing) {
  const Reader& reader = GetParam();
  const fs::path folder = bad_dir / reader.folder;
  const auto cases = read_expectations(folder);
  ASSERT_GE(cases.size(), 3u) << folder;
  // Every file of the folder has an expectation, and every expectation a file.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(folder)) files += entry.path().filename() != "expect.txt";
  EXPECT_EQ(files, cases.size());
  for (const auto& c : cases) {
    TempDir dir;
    write_text(dir / "job.gcode", "G0 X200 Y0\nM3 S500\nG1 X210 F600\nM5\n");
    const std::string path = (folder / c.file).string();
    const CliResult r = run_cli(replace(reader.command, path), dir.path());
    SCOPED_TRACE(path);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    std::string located = "error: " + path;
    if (c.where.find(':') != std::string::npos || std::isdigit(static_cast<unsigned char>(c.where[0]))) {
      located += ":" + c.where + ":";
    } else if (c.where != "-") {
      located += ": " + c.where;  // "record 3", "header"
    }
    EXPECT_NE(r.err.find(located), std::string::npos) << "expected '" << located << "' in:\n" << r.err;
    EXPECT_NE(r.err.find(c.value), std::string::npos) << "expected '" << c.value << "' in:\n" << r.err;
    EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
    if (*reader.output) {
      EXPECT_FALSE(fs::exists(dir / reader.output));
    }
    for (const auto& entry : fs::directory_iterator(dir.path())) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(EveryReader, BadInputs, ::testing::ValuesIn(readers),
                         [](const auto& param_info) { return std::string(param_info.param.folder); });

// The G-code corpus (tests/data/bad/gcode is tests/data/gcode_bad) through `run`: the first refusal of each
// file, exit 2, no joint file.
TEST(BadInputs, GcodeCorpusThroughRun) {
  const auto cases = read_corpus(fs::canonical(bad_dir / "gcode"));
  ASSERT_GE(cases.size(), 50u);
  for (const auto& c : cases) {
    TempDir dir;
    std::string flags;
    for (const auto& flag : c.flags) flags += " " + flag;
    const CliResult r = run_cli("run '" + c.path.string() + "'" + flags + " -o out.csv", dir.path());
    SCOPED_TRACE(c.path.filename().string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    ASSERT_FALSE(c.expected.empty());
    EXPECT_NE(r.err.find("error: " + c.expected.front()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.csv"));
  }
}

}  // namespace

namespace {

// Inputs the fuzzers found (tests/data/fuzz_regressions/<harness>/), replayed on every build: each once
// crashed or tripped a sanitizer. An empty JPEG segment made the in-memory reader call memcpy with a
// null destination (UBSan); the result, if any, must be a positive finite resolution.
TEST(FuzzRegressions, ImageMetadataInputsParseWithoutUndefinedBehaviour) {
  const fs::path dir = fs::path(STIFFPATH_TEST_DATA_DIR) / "fuzz_regressions" / "image_metadata";
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto r = stiffpath::vision::resolution_from_memory(bytes);
    if (r) {
      EXPECT_TRUE(std::isfinite(r->dpi_x) && r->dpi_x > 0 && std::isfinite(r->dpi_y) && r->dpi_y > 0) << entry.path();
    }
    ++count;
  }
  EXPECT_GE(count, 1u);
}

}  // namespace
