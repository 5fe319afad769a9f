// End-to-end tests of `stiffpath render-scan` and `stiffpath scan`: numbers against the ground truth, files, errors.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sys/wait.h>
#include <cmath>
#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

bool has_warning(const nlohmann::json& out, const std::string& part) {
  for (const auto& w : out["warnings"]) {
    if (w.get<std::string>().find(part) != std::string::npos) return true;
  }
  return false;
}

TEST(CliScan, RenderedLineMeasuresToItsTruth) {
  TempDir dir;
  const CliResult render = run_cli("render-scan line.png --length-mm 80 --angle-deg -1.4 --texture 0.01 --margin-mm 1.5 "
                                   "--seed 21 --truth truth.json --json", dir.path());
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const auto truth = render.json();
  EXPECT_EQ(truth, read_json(dir / "truth.json"));
  EXPECT_NEAR(truth["length_mm"].get<double>(), 80.0, 1e-9);

  const CliResult scan = run_cli("scan line.png --json", dir.path());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const auto out = scan.json();
  EXPECT_EQ(out["dpi_source"], "PNG pHYs");
  EXPECT_EQ(out["dpi"].get<double>(), 1200.0);
  EXPECT_NEAR(out["length_mm"].get<double>(), truth["length_mm"].get<double>(), 0.005);
  EXPECT_NEAR(out["width_mm"].get<double>(), truth["width_mm"].get<double>(), 0.002);
  EXPECT_LT(out["deviation_area_mm2"].get<double>(), 0.05);
  EXPECT_LT(out["max_deviation_mm"].get<double>(), 0.003);
  EXPECT_FALSE(out.contains("sides"));
  EXPECT_TRUE(out["warnings"].empty());

  // The resolution scales every length: at half the dpi the same pixels are twice as long.
  const CliResult half = run_cli("scan line.png --dpi 600 --json", dir.path());
  ASSERT_EQ(half.exit_code, 0) << half.err;
  EXPECT_EQ(half.json()["dpi_source"], "--dpi");
  // (Not to the last digit: the spline cutoff and the end fits are set in mm, so they span other pixels;
  // within the few-µm accuracy of each scan, at the doubled scale.)
  EXPECT_NEAR(half.json()["length_mm"].get<double>(), 2 * out["length_mm"].get<double>(), 3e-3);
  EXPECT_NEAR(half.json()["width_mm"].get<double>(), 2 * out["width_mm"].get<double>(), 1e-4);
}

TEST(CliScan, TriangleSidesCornersAndOverlay) {
  TempDir dir;
  ASSERT_EQ(run_cli("render-scan tri.png --shape triangle --side-mm 25 --angle-deg 2 --wiggle-mm 0.05 --wiggle-wavelength-mm 8 "
                    "--truth truth.json", dir.path()).exit_code, 0);
  const auto truth = read_json(dir / "truth.json");
  const CliResult scan = run_cli("scan tri.png --shape triangle --overlay over.png --json", dir.path());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const auto out = scan.json();
  ASSERT_EQ(out["sides"].size(), 3u);
  ASSERT_EQ(out["corners"].size(), 3u);
  EXPECT_TRUE(out["closed"].get<bool>());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(out["sides"][k]["length_mm"].get<double>(), truth["sides"][k]["length_mm"].get<double>(), 0.010);
    EXPECT_NEAR(out["corners"][k]["x_mm"].get<double>(), truth["corners"][k]["x_mm"].get<double>(), 0.010);
    EXPECT_NEAR(out["corners"][k]["angle_deg"].get<double>(), 60.0, 0.1);
    EXPECT_FALSE(out["corners"][k].contains("path_distance_mm"));  // not measured on scans
  }
  EXPECT_NEAR(out["deviation_area_mm2"].get<double>(), truth["deviation_area_mm2"].get<double>(),
              0.03 * truth["deviation_area_mm2"].get<double>());
  const cv::Mat overlay = cv::imread((dir / "over.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(overlay.empty());
  EXPECT_EQ(overlay.type(), CV_8UC3);
  // The scan at full scale, a legend above it and one deviation strip per side below it (the layout
  // itself is checked in tests/vision/test_overlay.cpp).
  EXPECT_GE(overlay.cols, out["image_px"][0].get<int>());
  EXPECT_GT(overlay.rows, out["image_px"][1].get<int>() + 3 * 5 * 14);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(CliScan, TiffJpegAndAPathFromCsv) {
  TempDir dir;
  ASSERT_EQ(run_cli("render-scan l.tif --length-mm 30 --bit-depth 16 --dpi 2400 --json > t.json", dir.path()).exit_code, 0);
  const CliResult tif = run_cli("scan l.tif --json", dir.path());
  ASSERT_EQ(tif.exit_code, 0) << tif.err;
  EXPECT_EQ(tif.json()["dpi_source"], "TIFF XResolution");
  EXPECT_NEAR(tif.json()["length_mm"].get<double>(), 30.0, 0.005);

  ASSERT_EQ(run_cli("render-scan l.jpg --length-mm 30 --colour", dir.path()).exit_code, 0);
  const CliResult jpg = run_cli("scan l.jpg --json", dir.path());
  ASSERT_EQ(jpg.exit_code, 0) << jpg.err;
  EXPECT_EQ(jpg.json()["dpi_source"], "JPEG JFIF");
  EXPECT_NEAR(jpg.json()["length_mm"].get<double>(), 30.0, 0.010);  // lossy compression costs a little

  write_text(dir / "path.csv", "x_mm,y_mm\n0,0\n7,0\n20,0\n26,8\n32,16\n");
  const CliResult render = run_cli("render-scan p.png --path-csv path.csv --sides 2 --json", dir.path());
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const auto truth = render.json();
  ASSERT_EQ(truth["sides"].size(), 2u);
  const CliResult scan = run_cli("scan p.png --shape polyline:2 --json", dir.path());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(scan.json()["sides"][k]["length_mm"].get<double>(), truth["sides"][k]["length_mm"].get<double>(), 0.005);
  }
}

TEST(CliScan, BadImagesExitWith2AndNoOutput) {
  TempDir dir;
  write_text(dir / "notes.png", "this is text, not an image\n");
  write_text(dir / "empty.png", "");
  cv::imwrite((dir / "blank.png").string(), cv::Mat(200, 600, CV_8U, cv::Scalar(220)));
  cv::Mat two(300, 1200, CV_8U, cv::Scalar(220));
  cv::line(two, {100, 100}, {1100, 100}, cv::Scalar(60), 9);
  cv::line(two, {100, 200}, {1000, 205}, cv::Scalar(60), 9);
  cv::imwrite((dir / "two.png").string(), two);
  const std::pair<const char*, const char*> cases[] = {{"notes.png", "not a readable image"},
                                                       {"empty.png", "the file is empty"},
                                                       {"missing.png", "no such file"},
                                                       {"blank.png", "no mark found"},
                                                       {"two.png", "found two separate marks"}};
  for (const auto& [file, message] : cases) {
    const CliResult r = run_cli(std::string("scan ") + file + " --overlay o.png --json", dir.path());
    EXPECT_EQ(r.exit_code, 2) << file;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_NE(r.err.find(std::string("error: ") + file + ": "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
  }
  ASSERT_EQ(run_cli("render-scan ok.png --length-mm 10", dir.path()).exit_code, 0);
  const CliResult shape = run_cli("scan ok.png --shape square", dir.path());
  EXPECT_EQ(shape.exit_code, 2);
  EXPECT_NE(shape.err.find("--shape: expected line, triangle, polyline:N"), std::string::npos) << shape.err;
  EXPECT_EQ(run_cli("scan ok.png --dpi -3", dir.path()).exit_code, 2);
  EXPECT_EQ(run_cli("render-scan bad.bmp --length-mm 10", dir.path()).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.bmp"));
}

TEST(CliScan, MissingResolutionIsAWarningInTheOutput) {
  TempDir dir;
  ASSERT_EQ(run_cli("render-scan l.png --length-mm 20", dir.path()).exit_code, 0);
  cv::imwrite((dir / "plain.png").string(), cv::imread((dir / "l.png").string(), cv::IMREAD_UNCHANGED));  // drops pHYs
  const CliResult r = run_cli("scan plain.png --json", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.json()["dpi_source"], "default");
  EXPECT_TRUE(has_warning(r.json(), "assumed 1200 dpi"));
  EXPECT_NEAR(r.json()["length_mm"].get<double>(), 20.0, 0.005);
  const CliResult text = run_cli("scan plain.png", dir.path());
  EXPECT_NE(text.out.find("warning: the file stores no resolution"), std::string::npos) << text.out;
  const auto at = text.out.find("length ");
  ASSERT_NE(at, std::string::npos) << text.out;
  EXPECT_NEAR(std::stod(text.out.substr(at + 7)), 20.0, 0.005) << text.out;  // a number, not its rounding
}

// A plate like the thesis's (fig. 4.7), shortened: a y line, an x line, a triangle and their labels.
constexpr const char* kPlate = R"({
  "page_mm": [70, 55],
  "marks": [
    {"shape": "line", "length_mm": 40, "angle_deg": 90, "at_mm": [8, 8], "wiggle_mm": 0.05, "wiggle_wavelength_mm": 7},
    {"shape": "line", "length_mm": 30, "at_mm": [25, 50], "wiggle_mm": 0.04, "wiggle_wavelength_mm": 6},
    {"shape": "polyline", "vertices_mm": [[0, 0], [20, 0], [10, -25]], "closed": true, "at_mm": [30, 38]}
  ],
  "labels": [{"text": "Y 5G", "at_mm": [11, 6], "height_mm": 3}, {"text": "X 5G", "at_mm": [25, 46], "height_mm": 3},
             {"text": "TRI", "at_mm": [52, 38], "height_mm": 3}]
})";

// The truth whose box holds box_mm (x, y, w, h), or null.
const nlohmann::json* truth_for(const nlohmann::json& truth, const nlohmann::json& box) {
  for (const auto& t : truth["marks"]) {
    const auto& b = t["box_mm"];
    if (box[0].get<double>() >= b[0].get<double>() - 0.5 && box[1].get<double>() >= b[1].get<double>() - 0.5 &&
        box[0].get<double>() + box[2].get<double>() <= b[0].get<double>() + b[2].get<double>() + 0.5 &&
        box[1].get<double>() + box[3].get<double>() <= b[1].get<double>() + b[3].get<double>() + 0.5) {
      return &t;
    }
  }
  return nullptr;
}

TEST(CliScan, PlateWithEveryMarkMeasuredAndRegionsInMmOrPixels) {
  TempDir dir;
  write_text(dir / "plate.json", kPlate);
  const CliResult render = run_cli("render-scan plate.png --plate plate.json --texture 0.01 --specks 10 --seed 4 --truth truth.json",
                                   dir.path());
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const auto truth = read_json(dir / "truth.json");
  ASSERT_EQ(truth["marks"].size(), 3u);
  EXPECT_NE(render.out.find("truth of mark 3"), std::string::npos) << render.out;

  const CliResult all = run_cli("scan plate.png --all-marks --overlay over.png --json", dir.path());
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const auto out = all.json();
  EXPECT_EQ(out["measured"], 3);
  EXPECT_EQ(out["skipped"], 0);
  EXPECT_EQ(out["labels"].size(), 3u);
  std::vector<std::string> shapes;
  for (const auto& m : out["marks"]) {
    ASSERT_EQ(m["status"], "measured") << m.dump();
    const auto* t = truth_for(truth, m["box_mm"]);
    ASSERT_NE(t, nullptr) << m["box_mm"].dump();
    shapes.push_back(m["shape"]);
    const double sides = m.contains("sides") ? static_cast<double>(m["sides"].size()) : 1.0;
    EXPECT_NEAR(m["length_mm"].get<double>(), (*t)["length_mm"].get<double>(), 0.005 * sides) << m["shape"];
  }
  EXPECT_EQ(shapes, (std::vector<std::string>{"line", "triangle", "line"}));
  const cv::Mat overlay = cv::imread((dir / "over.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(overlay.empty());
  EXPECT_GT(overlay.rows, out["image_px"][1].get<int>());

  // One mark by itself: the plate is refused, a region around the x line (mm) measures it, the same
  // region in pixels measures the same pixels.
  const CliResult one = run_cli("scan plate.png", dir.path());
  EXPECT_EQ(one.exit_code, 2);
  EXPECT_NE(one.err.find("--all-marks"), std::string::npos) << one.err;
  const CliResult x_mm = run_cli("scan plate.png --roi 22,47,36,6 --json", dir.path());
  ASSERT_EQ(x_mm.exit_code, 0) << x_mm.err;
  const auto* x_truth = truth_for(truth, nlohmann::json::array({25.0, 49.9, 30.0, 0.2}));
  ASSERT_NE(x_truth, nullptr);
  EXPECT_NEAR(x_mm.json()["length_mm"].get<double>(), (*x_truth)["length_mm"].get<double>(), 0.005);
  EXPECT_EQ(x_mm.json()["roi_mm"].size(), 4u);
  const int px = static_cast<int>(std::lround(22 * 1200 / 25.4)), py = static_cast<int>(std::lround(47 * 1200 / 25.4));
  const int pw = static_cast<int>(std::lround(58 * 1200 / 25.4)) - px, ph = static_cast<int>(std::lround(53 * 1200 / 25.4)) - py;
  const CliResult x_px = run_cli(fmt::format("scan plate.png --roi {},{},{},{}px --json", px, py, pw, ph), dir.path());
  ASSERT_EQ(x_px.exit_code, 0) << x_px.err;
  EXPECT_EQ(x_px.json()["length_mm"], x_mm.json()["length_mm"]);
  for (const auto& [roi, message] : std::vector<std::pair<std::string, std::string>>{{"22,47,36", "expected X,Y,W,H"},
                                                                                     {"22,47,-36,6", "W and H numbers > 0"},
                                                                                     {"22,47,60,6", "reaches beyond the image"},
                                                                                     {"22,47,36,6in", "expected X,Y,W,H"}}) {
    const CliResult bad = run_cli("scan plate.png --roi " + roi, dir.path());
    EXPECT_EQ(bad.exit_code, 2) << roi;
    EXPECT_NE(bad.err.find(message), std::string::npos) << roi << ": " << bad.err;
  }
}

// The issue's chain, as a user runs it: the robot's own uncompensated 5 g triangle, simulated, rendered
// and scanned as a closed triangle, within 5 µm of the render's truth (it read 3.3 mm short).
TEST(CliScan, TheTwinsUncompensatedTriangleScansToItsTruth) {
  TempDir dir;
  const std::string gcode = std::string(STIFFPATH_SOURCE_DIR) + "/examples/triangle.gcode";
  ASSERT_EQ(run_cli("run '" + gcode + "' --accel 5g --no-compensation -o j.csv", dir.path()).exit_code, 0);
  // The matched twin (the mark this check was built on): the honest twin's uncompensated corners overshoot
  // 0.5 mm and fold back onto the side, which the scan refuses at the default 1 mm corner trim.
  const CliResult simulated = run_cli(
      "simulate j.csv --sides 3 --marks-csv marks.csv --truth physical --servo ideal --no-cg-lever --json", dir.path());
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const CliResult render = run_cli("render-scan tri.png --path-csv marks.csv --sides 3 --json", dir.path());
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const CliResult scan = run_cli("scan tri.png --shape triangle --json", dir.path());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const auto truth = render.json(), out = scan.json();
  EXPECT_TRUE(out["closed"].get<bool>());
  EXPECT_EQ(out["shape"], "triangle");
  EXPECT_NEAR(out["length_mm"].get<double>(), truth["length_mm"].get<double>(), 0.005);
  EXPECT_TRUE(out["warnings"].empty()) << out["warnings"].dump();
  EXPECT_EQ(out["length_uncertainty_mm"].get<double>(), 0.0);
  // One mark metric: the scan of the simulated mark gives simulate's own numbers (both measure along the mark).
  const auto sim = simulated.json();
  EXPECT_NEAR(out["length_mm"].get<double>(), sim["length_mm"].get<double>(), 0.005);
  EXPECT_NEAR(out["max_deviation_mm"].get<double>(), sim["max_deviation_mm"].get<double>(), 0.005);
}

// Runs a command on a pseudo-terminal (util-linux script) and returns what the terminal showed.
std::string on_terminal(const std::string& args, const std::filesystem::path& cwd) {
  const std::string command = "cd '" + cwd.string() + "' && STIFFPATH_PROGRESS_DELAY_S=0 script -qec \"'" + std::string(STIFFPATH_CLI) +
                              "' " + args + "\" /dev/null";
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return out;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  ::pclose(pipe);
  return out;
}

TEST(CliScan, ProgressOnATerminalOnlyAndNeverWithQuiet) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "no util-linux script for a pseudo-terminal";
  TempDir dir;
  const std::string terminal_render = on_terminal("render-scan l.png --length-mm 60", dir.path());
  EXPECT_NE(terminal_render.find("render-scan ["), std::string::npos) << terminal_render;
  EXPECT_NE(terminal_render.find("100%"), std::string::npos) << terminal_render;
  const std::string terminal = on_terminal("scan l.png", dir.path());
  EXPECT_NE(terminal.find("scan ["), std::string::npos) << terminal;
  EXPECT_NE(terminal.find("length 60.00"), std::string::npos) << terminal;  // the result still follows
  const std::string quiet = on_terminal("scan l.png --quiet", dir.path());
  EXPECT_EQ(quiet.find("scan ["), std::string::npos) << quiet;
  EXPECT_NE(quiet.find("length 60.00"), std::string::npos) << quiet;
  // Not a terminal (a pipe and a file, as in scripts): nothing but the result, even with no delay.
  const CliResult piped = run_cli("scan l.png", dir.path());
  EXPECT_EQ(piped.err.find('['), std::string::npos) << piped.err;
  EXPECT_EQ(piped.out.find('\r'), std::string::npos);
}

// The centre line of every mark, in the CSV and in the JSON: the same points, in scan mm from the image's
// top-left corner (y down), lying on the rendered path (the truth's), with each side's ends at the path's ends.
TEST(CliScan, CentreLinesOfEveryMarkInTheCsvAndTheJson) {
  TempDir dir;
  write_text(dir / "plate.json", R"({"page_mm": [60, 40], "marks": [
    {"shape": "line", "length_mm": 30, "at_mm": [10, 10], "angle_deg": 4},
    {"shape": "polyline", "vertices_mm": [[0, 0], [20, 0], [20, 15]], "at_mm": [30, 20]}]})");
  const CliResult render = run_cli("render-scan plate.png --plate plate.json --texture 0.01 --seed 9 --json", dir.path());
  ASSERT_EQ(render.exit_code, 0) << render.err;
  const CliResult scan = run_cli("scan plate.png --all-marks --centre-line-csv lines.csv --json", dir.path());
  ASSERT_EQ(scan.exit_code, 0) << scan.err;
  const auto out = scan.json();
  ASSERT_EQ(out["measured"], 2);
  std::ifstream csv(dir / "lines.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_NE(line.find("top-left corner of its image"), std::string::npos) << line;  // the frame, said in the file
  EXPECT_NE(line.find("y down"), std::string::npos) << line;
  std::getline(csv, line);
  EXPECT_EQ(line, "mark,side,x_mm,y_mm");
  std::map<std::pair<int, int>, std::vector<std::array<double, 2>>> rows;
  while (std::getline(csv, line)) {
    int mark = 0, side = 0;
    double x = 0, y = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%d,%lf,%lf", &mark, &side, &x, &y), 4) << line;
    rows[{mark, side}].push_back({x, y});
  }
  ASSERT_EQ(rows.size(), 3u);  // a line and a two-sided polyline
  // The truth's paths, for the distance of each point from the path it was drawn along.
  const auto truth = render.json();
  for (const auto& m : out["marks"]) {
    const int index = m["index"].get<int>();
    const auto& sides = m["centre_line"]["sides_mm"];
    EXPECT_EQ(m["centre_line"]["frame"].get<std::string>().find("mm of the scan"), 0u);
    for (std::size_t k = 0; k < sides.size(); ++k) {
      const auto& points = rows[{index, static_cast<int>(k) + 1}];
      ASSERT_EQ(points.size(), sides[k].size()) << index << " " << k;
      for (std::size_t i = 0; i < points.size(); i += 97) {
        EXPECT_NEAR(points[i][0], sides[k][i][0].get<double>(), 1.5e-4);  // both to 0.1 µm, rounded apart
        EXPECT_NEAR(points[i][1], sides[k][i][1].get<double>(), 1.5e-4);
      }
    }
  }
  // The line's points lie on the rendered line (30 mm from (10, 10) at 4°), within a few µm, ends included.
  const auto& line_points = rows[{1, 1}];
  const double c = std::cos(4 * std::acos(-1.0) / 180), sn = std::sin(4 * std::acos(-1.0) / 180);
  for (const auto& p : line_points) {
    const double along = (p[0] - 10) * c + (p[1] - 10) * sn, across = -(p[0] - 10) * sn + (p[1] - 10) * c;
    EXPECT_NEAR(across, 0.0, 0.004);
    EXPECT_GE(along, -0.005);
    EXPECT_LE(along, 30.005);
  }
  EXPECT_NEAR(line_points.front()[0], 10.0, 0.005);
  EXPECT_NEAR(line_points.back()[0], 10 + 30 * c, 0.005);
  // An output is never the scan itself.
  const CliResult same = run_cli("scan plate.png --all-marks --centre-line-csv plate.png", dir.path());
  EXPECT_EQ(same.exit_code, 2);
  EXPECT_NE(same.err.find("an output never replaces an input"), std::string::npos) << same.err;
  EXPECT_FALSE(cv::imread((dir / "plate.png").string()).empty());
}

// Options in range that ask for more than the renderer's budget are refused before any work, naming the
// budget and the options (this one asked for 2e8 path points, 5.3 GB, and ended in bad_alloc, exit 1).
TEST(CliScan, ARenderBeyondItsBudgetIsRefusedBeforeTheWork) {
  TempDir dir;
  const CliResult r = run_cli("render-scan big.png --length-mm 2000 --wiggle-mm 0.1 --wiggle-wavelength-mm 0.001 --dpi 10", dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--wiggle-wavelength-mm 0.001"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("render budget of 5000000 points"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "big.png"));
  const CliResult wide = run_cli("render-scan wide.png --length-mm 2000 --margin-mm 900", dir.path());
  EXPECT_EQ(wide.exit_code, 2) << wide.err;
  EXPECT_NE(wide.err.find("200 Mpx"), std::string::npos) << wide.err;
}

// Whatever the memory limit, scan and render-scan end with exit 0 or a refusal (2) that names the limit,
// never an internal error (a scan that could not start OpenCV's threads once said "internal error:
// pthread_create has failed"). Below the limit the program cannot even load (exit 127), it is not counted.
TEST(CliScan, RunningOutOfMemoryIsARefusalThatNamesTheLimit) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "sanitizers reserve far more address space than any limit tried here";
#else
  TempDir dir;
  ASSERT_EQ(run_cli("render-scan l.png --length-mm 60 --texture 0.01", dir.path()).exit_code, 0);
  int refused = 0, measured = 0;
  for (int limit_mb = 120; limit_mb <= 420; limit_mb += 20) {
    const std::string command = "cd '" + dir.path().string() + "' && ulimit -v " + std::to_string(limit_mb * 1024) + " && '" +
                                std::string(STIFFPATH_CLI) + "' scan l.png --json >/dev/null 2>err.txt";
    const int status = std::system(("/bin/bash -c \"" + command + "\"").c_str());
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream err(dir / "err.txt");
    const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
    if (code == 127) continue;
    EXPECT_TRUE(code == 0 || code == 2) << limit_mb << " MiB: exit " << code << ": " << text;
    EXPECT_EQ(text.find("internal error"), std::string::npos) << limit_mb << " MiB: " << text;
    if (code == 2) {
      ++refused;
      EXPECT_NE(text.find("l.png: RESOURCE: out of memory"), std::string::npos) << text;
      EXPECT_NE(text.find("ulimit -v"), std::string::npos) << text;
    }
    measured += code == 0 ? 1 : 0;
  }
  EXPECT_GE(measured, 1);
  std::printf("[limits] scan under ulimit -v 120..420 MiB: %d refused naming the limit, %d measured\n", refused, measured);
#endif
}

}  // namespace
}  // namespace stiffpath::test
