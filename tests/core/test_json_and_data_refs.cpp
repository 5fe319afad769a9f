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
  const auto at = [](std::string_view path) { return locate_json_path(kDoc, path).value(); };
  EXPECT_EQ(at("name"), std::make_pair(2, 3));
  EXPECT_EQ(at("cg"), std::make_pair(3, 3));
  EXPECT_EQ(at("cg.label"), std::make_pair(3, 10));
  EXPECT_EQ(at("cg.h"), std::make_pair(3, 24));
  EXPECT_EQ(at("joints"), std::make_pair(4, 3));
  EXPECT_EQ(at("joints[0]"), std::make_pair(5, 5));
  EXPECT_EQ(at("joints[1].max"), std::make_pair(6, 6));
  EXPECT_EQ(at("joints[1].esc\"aped"), std::make_pair(6, 18));
  EXPECT_FALSE(locate_json_path(kDoc, "joints[2]").has_value());
  EXPECT_FALSE(locate_json_path(kDoc, "cg.lab").has_value());  // a prefix of a key is not the key
  EXPECT_FALSE(locate_json_path(kDoc, "max").has_value());      // nor is a key of a nested object

  // The members of one object, in file order, without those of the objects inside it.
  const auto root = json_object_members(kDoc, "");
  ASSERT_EQ(root.size(), 3U);
  EXPECT_EQ(root[0].key, "name");
  EXPECT_EQ(root[2].key, "joints");
  EXPECT_EQ(std::make_pair(root[2].line, root[2].column), std::make_pair(4, 3));
  const auto second = json_object_members(kDoc, "joints[1]");
  ASSERT_EQ(second.size(), 2U);
  EXPECT_EQ(second[1].key, "esc\"aped");
  EXPECT_EQ(std::make_pair(second[1].line, second[1].column), std::make_pair(6, 18));
  EXPECT_TRUE(json_object_members(kDoc, "joints").empty());  // an array has no keys
}

// Depth and size are bounded before parsing, at the bracket that crosses the limit; the walk that
// locates keys needs no recursion, so the deepest text allowed costs nothing special.
TEST(JsonKeys, DepthAndSizeAreBoundedAndLocated) {
  const int n = max_json_depth;
  const std::string ok = std::string(n, '[') + std::string(n, ']');
  EXPECT_NO_THROW((void)parse_json(ok, "ok.json"));
  const std::string deep = "{\n  \"a\": " + std::string(n, '[') + std::string(n, ']') + "}";
  try {
    (void)parse_json(deep, "deep.json");
    FAIL();
  } catch (const Error& e) {
    // the 65th opening bracket: "{" is the first, then column 8 holds the first "[" on line 2
    EXPECT_EQ(std::string(e.what()), "deep.json:2:" + std::to_string(8 + n - 1) +
                                         ": LIMIT: nested more than 64 levels deep (objects and arrays)");
  }
  // brackets inside strings do not count
  EXPECT_NO_THROW((void)parse_json("{\"a\": \"" + std::string(1000, '[') + "\\\"\"}", "s.json"));
  const std::string big(max_json_bytes + 1, ' ');
  try {
    (void)parse_json(big, "big.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("big.json: LIMIT: 8388609 bytes"), std::string::npos) << e.what();
  }
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
