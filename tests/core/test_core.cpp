// Tests of the core module: CSV reading with precise errors, atomic output, JSON fields, units.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "cli_runner.hpp"
#include "stiffpath/core/atomic_file.hpp"
#include "stiffpath/core/csv.hpp"
#include "stiffpath/core/embedded.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"
#include "stiffpath/core/units.hpp"

namespace stiffpath::core {
namespace {

TEST(Csv, ReadsRowsSkippingCommentsAndBlankLines) {
  std::istringstream in("# comment\nx_mm,name\n1.5,\"a,b\"\n\n-2e-3, c \n");
  CsvReader csv(in, "t.csv");
  const auto x = csv.column("x_mm"), name = csv.column("name");
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.line(), 3);
  EXPECT_DOUBLE_EQ(csv.number(x), 1.5);
  EXPECT_EQ(csv.text(name), "a,b");
  ASSERT_TRUE(csv.next());
  EXPECT_EQ(csv.line(), 5);
  EXPECT_DOUBLE_EQ(csv.number(x), -2e-3);
  EXPECT_EQ(csv.text(name), "c");
  EXPECT_FALSE(csv.next());
}

TEST(Csv, ErrorsNameFileLineColumnAndValue) {
  std::istringstream in("a,b\n1,2\n3,nan\n");
  CsvReader csv(in, "f.csv");
  ASSERT_TRUE(csv.next());
  ASSERT_TRUE(csv.next());
  try {
    (void)csv.number(1);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "f.csv:3:3: column 'b': 'nan' is not a finite number");
  }
  EXPECT_THROW((void)csv.column("c"), Error);
  std::istringstream commented("# a comment\n\nx,y\n1,2\n");
  CsvReader with_comment(commented, "h.csv");
  try {
    (void)with_comment.column("z");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 3);  // the header's own line, after the comment and the blank line
  }
  std::istringstream ragged("a,b\n1\n");
  CsvReader r(ragged, "g.csv");
  try {
    (void)r.next();
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "g.csv:2: row has 1 fields, the header has 2");
  }
}

TEST(Csv, OptionalNumberTreatsEmptyAsMissing) {
  std::istringstream in("a\n\"\"\n");
  CsvReader csv(in, "m.csv");
  ASSERT_TRUE(csv.next());
  EXPECT_FALSE(csv.optional_number(0).has_value());
  EXPECT_THROW((void)csv.number(0), Error);
}

TEST(AtomicFile, LeavesNothingBehindWithoutCommit) {
  test::TempDir dir;
  const auto path = dir / "out.csv";
  {
    AtomicFile file(path);
    file.stream() << "partial";
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
  {
    AtomicFile file(path);
    file.stream() << "done";
    file.commit();
  }
  EXPECT_EQ(std::filesystem::file_size(path), 4u);
  EXPECT_THROW(AtomicFile(dir / "no" / "such" / "dir.csv"), Error);
}

TEST(Json, SyntaxErrorsCarryLineAndColumn) {
  try {
    (void)parse_json("{\n \"a\": 1,\n \"b\": ]\n}", "doc.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.where().file, "doc.json");
  }
}

TEST(Units, AccelerationParsing) {
  EXPECT_DOUBLE_EQ(units::parse_acceleration_m_s2("5g"), 5 * 9.80665);
  EXPECT_DOUBLE_EQ(units::parse_acceleration_m_s2("2.5 g"), 2.5 * 9.80665);
  EXPECT_DOUBLE_EQ(units::parse_acceleration_m_s2("30"), 30.0);
  EXPECT_DOUBLE_EQ(units::parse_acceleration_m_s2("30 m/s2"), 30.0);
  EXPECT_THROW((void)units::parse_acceleration_m_s2("-1g"), Error);
  EXPECT_THROW((void)units::parse_acceleration_m_s2("5 furlongs"), Error);
  EXPECT_THROW((void)units::parse_acceleration_m_s2("g"), Error);
  EXPECT_DOUBLE_EQ(units::kgf_to_N(24.86), 24.86 * 9.80665);
}

TEST(Embedded, PresetsAreBuiltIn) {
  const auto text = find_embedded("robots/oc-gu.json");
  ASSERT_TRUE(text.has_value());
  EXPECT_NE(text->find("\"oc-gu\""), std::string_view::npos);
  EXPECT_FALSE(find_embedded("robots/none.json").has_value());
}

}  // namespace
}  // namespace stiffpath::core

#include "stiffpath/core/sha256.hpp"

namespace stiffpath::core {
namespace {
TEST(Sha256, FipsTestVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}
}  // namespace
}  // namespace stiffpath::core
