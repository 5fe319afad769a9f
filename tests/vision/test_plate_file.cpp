// Plate files: every field read and checked where it is, unknown keys and things off the page refused at their line and column.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_runner.hpp"
#include "stiffpath/core/error.hpp"
#include "stiffpath/vision/render/plate.hpp"

namespace stiffpath::vision {
namespace {

std::filesystem::path write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

// The refusal of loading (and rendering, when loading passes) a plate file.
std::string refusal(const std::filesystem::path& file) {
  try {
    const Plate plate = load_plate(file);
    RenderOptions o;
    o.dpi = 100;
    (void)render_plate(plate, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

TEST(PlateFile, AFullPlateIsReadWithIdsFiducialsAndTheScannerBed) {
  test::TempDir dir;
  write(dir, "path.csv", "x_mm,y_mm\n0,0\n10,0\n10,5\n");
  const auto file = write(dir, "plate.json", R"({
  "comment": "a plate",
  "page_mm": [100, 80],
  "marks": [
    {"id": "x-5g", "shape": "line", "length_mm": 40, "at_mm": [10, 20], "angle_deg": 3, "wiggle_mm": 0.1},
    {"id": "poly", "shape": "polyline", "vertices_mm": [[0, 0], [20, 0], [20, 10]], "at_mm": [50, 40]},
    {"path_csv": "path.csv", "sides": 2, "at_mm": [20, 60]}
  ],
  "fiducials": [{"at_mm": [8, 8]}, {"at_mm": [92, 8], "radius_mm": 2.5, "cross": false}],
  "labels": [{"text": "X 5G", "at_mm": [10, 16], "height_mm": 3}],
  "scanner": {"bed_mm": [110, 90], "page_at_mm": [4, 5], "page_angle_deg": 1.5, "mirror": true, "smudges": 2}
})");
  const Plate plate = load_plate(file);
  ASSERT_EQ(plate.marks.size(), 3u);
  EXPECT_EQ(plate.marks[0].id, "x-5g");
  EXPECT_EQ(plate.marks[0].where.line, 5);  // the mark's own line in the file
  EXPECT_EQ(plate.marks[2].sides.size(), 2u);
  ASSERT_EQ(plate.fiducials.size(), 2u);
  EXPECT_DOUBLE_EQ(plate.fiducials[1].shape.ring_radius_m, 2.5e-3);
  EXPECT_FALSE(plate.fiducials[1].shape.cross);
  EXPECT_DOUBLE_EQ(plate.fiducials[0].shape.cross_arm_m, 1.5e-3);  // half the radius by default
  ASSERT_TRUE(plate.bed.has_value());
  EXPECT_TRUE(plate.bed->mirror);
  EXPECT_DOUBLE_EQ(plate.bed->width_m, 0.110);
  RenderOptions o;
  o.dpi = 150;
  const RenderedPlate rendered = render_plate(plate, o);
  EXPECT_EQ(rendered.image.cols, static_cast<int>(std::ceil(0.110 * 150 / 0.0254)));
  EXPECT_EQ(rendered.marks[0].id, "x-5g");
  EXPECT_EQ(rendered.fiducials_m.size(), 2u);
}

// Each bad field is named with its file, line and column.
TEST(PlateFile, BadFieldsAreRefusedAtTheirLineAndColumn) {
  test::TempDir dir;
  struct Case {
    const char* name;
    std::string text;
    std::string located;  // "line:column: path" the message must hold
  };
  const std::string page = R"("page_mm": [100, 80],)";
  const Case cases[] = {
      {"unknown_root_key.json", "{\n" + page + "\n\"colour\": \"red\", \"marks\": []}", "3:1: colour: unknown field"},
      {"unknown_mark_key.json", "{\n" + page + "\n\"marks\": [\n{\"shape\": \"line\", \"length_mm\": 10, \"at_mm\": [5, 5], \"lenght_mm\": 12}]}",
       "4:53: marks[0].lenght_mm: unknown field"},
      {"vertex_4e9_mm.json", "{\n" + page + "\n\"marks\": [{\"shape\": \"polyline\", \"at_mm\": [5, 5],\n\"vertices_mm\": [[0, 0],\n[4.3e9, 0]]}]}",
       "5:1: marks[0].vertices_mm[1]: RANGE"},
      {"label_off_the_page.json", "{\n" + page + "\n\"marks\": [],\n\"labels\": [{\"text\": \"LONG LABEL\", \"at_mm\": [80, 40], \"height_mm\": 5}]}",
       "4:12: label 'LONG LABEL'"},
      {"fiducial_off_the_page.json", "{\n" + page + "\n\"marks\": [],\n\"fiducials\": [{\"at_mm\": [99, 40]}]}", "4:15: fiducial 1"},
      {"mark_off_the_bed.json",
       "{\n" + page + "\n\"marks\": [{\"shape\": \"line\", \"length_mm\": 90, \"at_mm\": [5, 5]}],\n\"scanner\": {\"bed_mm\": [60, 60]}}",
       "3:11: mark 1 lies off the scanner's bed"},
      {"unknown_scanner_key.json", "{\n" + page + "\n\"marks\": [],\n\"scanner\": {\"bed_mm\": [60, 60], \"lid\": 1}}", "4:33: scanner.lid: unknown field"},
  };
  for (const Case& c : cases) {
    const auto file = write(dir, c.name, c.text);
    const std::string what = refusal(file);
    EXPECT_NE(what.find(file.string() + ":" + c.located), std::string::npos) << c.name << ": " << what;
  }
}

// A path file's coordinates are checked where they enter (a 1e7 mm coordinate once ran out of memory).
TEST(PlateFile, APathFileBeyondAnyPlateIsRefusedAtItsCell) {
  test::TempDir dir;
  const auto file = write(dir, "far.csv", "x_mm,y_mm\n0,0\n1e7,0\n");
  try {
    (void)load_mark_csv(file, 1);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ":3:1:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("RANGE"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stiffpath::vision
