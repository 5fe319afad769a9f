// End-to-end tests of `stiffpath render-scan` and `stiffpath scan`: numbers against the ground truth, files, errors.
#include <gtest/gtest.h>

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
  // (Not to the last digit: the spline cutoff and the end fits are set in mm, so they span other pixels.)
  EXPECT_NEAR(half.json()["length_mm"].get<double>(), 2 * out["length_mm"].get<double>(), 1e-3);
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
  EXPECT_EQ(overlay.cols, out["image_px"][0].get<int>());
  EXPECT_EQ(overlay.rows, out["image_px"][1].get<int>() + 3 * 140);  // the scan and one deviation strip per side
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
  EXPECT_NE(shape.err.find("--shape: expected line, triangle or polyline:N"), std::string::npos) << shape.err;
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

}  // namespace
}  // namespace stiffpath::test
