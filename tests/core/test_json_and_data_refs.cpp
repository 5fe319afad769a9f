// Tests of JSON key positions, located field errors, unknown keys, and data references beside their file or built in.
#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "stiffpath/core/data_ref.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/core/json_fields.hpp"

namespace stiffpath::core {
namespace {

// Positions counted by hand: line 1 is "{", keys start after two spaces (column 3).
const char* kDoc =
    "{\n"
    "  \"name\": \"r\",\n"
    "  \"cg\": {\"label\": \"G\", \"h\": 1},\n"
    "  \"joints\": [\n"
    "    {\"max\": 2},\n"
    "    {\"max\": \"x\", \"esc\\\"aped\": 0}\n"
    "  ]\n"
    "}\n";

TEST(JsonKeys, EveryKeyAndArrayElementHasItsLineAndColumn) {
  const JsonKeyIndex keys = index_json_keys(kDoc);
  EXPECT_EQ(keys.at("name"), std::make_pair(2, 3));
  EXPECT_EQ(keys.at("cg"), std::make_pair(3, 3));
  EXPECT_EQ(keys.at("cg.label"), std::make_pair(3, 10));
  EXPECT_EQ(keys.at("cg.h"), std::make_pair(3, 24));
  EXPECT_EQ(keys.at("joints"), std::make_pair(4, 3));
  EXPECT_EQ(keys.at("joints[0]"), std::make_pair(5, 5));
  EXPECT_EQ(keys.at("joints[1].max"), std::make_pair(6, 6));
  EXPECT_EQ(keys.at("joints[1].esc\"aped"), std::make_pair(6, 18));
  EXPECT_EQ(keys.size(), 10U);
}

TEST(JsonKeys, FieldErrorsPointAtTheKey) {
  const JsonDocument doc = parse_json_document(kDoc, "r.json");
  const JsonObject root(doc);
  try {
    (void)root.element("joints", 1).number("max");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "r.json:6:6: joints[1].max: must be a number, got string \"x\"");
  }
  try {
    (void)root.object("cg").positive("missing");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "r.json:3:3: cg.missing: missing field");  // at the object that lacks it
  }
  try {
    root.object("cg").allow_only({"label"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "r.json:3:24: cg.h: unknown field");
  }
  // Of several unknown keys, the first in the file is named (not the first alphabetically).
  const JsonDocument two = parse_json_document("{\"zeta\": 1,\n \"alpha\": 2}", "t.json");
  try {
    JsonObject(two).allow_only({}, {{"alpha", "did you mean beta?"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "t.json:1:2: zeta: unknown field");
  }
  try {
    JsonObject(two).allow_only({"zeta"}, {{"alpha", "did you mean beta?"}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "t.json:2:2: alpha: unknown field (did you mean beta?)");
  }
}

TEST(JsonKeys, PairAndSignAreChecked) {
  const JsonDocument doc = parse_json_document("{\"p\": [1, 2], \"q\": [1], \"s\": -1, \"t\": 0.5}", "d.json");
  const JsonObject root(doc);
  EXPECT_EQ(root.pair("p"), std::make_pair(1.0, 2.0));
  EXPECT_THROW((void)root.pair("q"), Error);
  EXPECT_EQ(root.sign("s"), -1);
  EXPECT_THROW((void)root.sign("t"), Error);
}

TEST(DataRef, ResolvesBesideItsFileBuiltInOrOnDisk) {
  const DataRef on_disk{"robots/mine/robot.json", false};
  EXPECT_EQ(resolve_beside(on_disk, "data/t.csv"), (DataRef{"robots/mine/data/t.csv", false}));
  EXPECT_EQ(resolve_beside(on_disk, "../t.csv"), (DataRef{"robots/t.csv", false}));
  EXPECT_EQ(resolve_beside(on_disk, "/abs/t.csv"), (DataRef{"/abs/t.csv", false}));
  EXPECT_EQ(resolve_beside(on_disk, "builtin:thesis/displacements.csv"), (DataRef{"thesis/displacements.csv", true}));
  const DataRef preset{"robots/oc-gu.json", true};
  EXPECT_EQ(resolve_beside(preset, "../thesis/displacements.csv"), (DataRef{"thesis/displacements.csv", true}));
  EXPECT_EQ(parse_data_ref("builtin:x/y.csv"), (DataRef{"x/y.csv", true}));
  EXPECT_EQ((DataRef{"x/y.csv", true}).label(), "builtin:x/y.csv");
  EXPECT_TRUE(data_exists({"thesis/displacements.csv", true}));
  EXPECT_FALSE(data_exists({"thesis/nothing.csv", true}));
  EXPECT_EQ(read_data({"robots/oc-gu.json", true}).find("\"name\": \"oc-gu\"") != std::string::npos, true);
  try {
    (void)read_data({"thesis/nothing.csv", true});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "builtin:thesis/nothing.csv: no such file is built into this binary");
  }
  test::TempDir dir;
  test::write_text(dir / "f.txt", "abc");
  EXPECT_EQ(read_data({(dir / "f.txt").string(), false}), "abc");
  EXPECT_THROW((void)read_data({(dir / "g.txt").string(), false}), Error);
}

}  // namespace
}  // namespace stiffpath::core
