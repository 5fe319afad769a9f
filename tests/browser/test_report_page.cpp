// The HTML report in a real browser: headless Chromium loads it, its own script counts the drawn figures, and the screenshot is not blank.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <sstream>

#include "cli_runner.hpp"

namespace stiffpath::test {
namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Debian's `chromium`; Chrome's names elsewhere. Empty when none is installed.
std::string browser() {
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    if (std::system((std::string("command -v ") + name + " >/dev/null 2>&1").c_str()) == 0) return name;
  }
  return {};
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(ReportPage, LoadsEveryFigureInHeadlessChromium) {
  const std::string chromium = browser();
  if (chromium.empty()) {
    // CI installs it (scripts/bootstrap.sh browser) and sets STIFFPATH_REQUIRE_BROWSER, so it cannot skip there.
    if (std::getenv("STIFFPATH_REQUIRE_BROWSER") != nullptr) FAIL() << "STIFFPATH_REQUIRE_BROWSER is set but chromium is missing";
    GTEST_SKIP() << "chromium is not installed (scripts/bootstrap.sh browser)";
  }
  TempDir dir;
  const std::string examples = std::string(STIFFPATH_SOURCE_DIR) + "/examples/";
  ASSERT_EQ(run_cli("run " + examples + "y_motion.gcode --accel 5g -o joints.csv", dir.path()).exit_code, 0);
  ASSERT_EQ(run_cli("experiment -o exp --robots oc-gu --motions y --accelerations-g 1 3 --quiet", dir.path()).exit_code, 0);
  const CliResult r = run_cli("report --robot oc-gu --joints joints.csv --experiment exp -o rep --quiet", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto page = dir.path() / "rep" / "report.html";
  const std::string html = read_text(page);
  // Self-contained: no external resources (the only URLs are the SVG name spaces).
  EXPECT_EQ(count(html, " src="), 0U);
  EXPECT_EQ(count(html, "<link"), 0U);
  EXPECT_EQ(count(html, "http"), count(html, "http://www.w3.org/"));
  const std::size_t figures = count(html, "<figure data-figure=");
  EXPECT_EQ(figures, 6U);  // compliance map, cross-validation, run motion and joints, figs. 4.9a and 4.9b
  for (const char* section : {"Robot and data provenance", "Data checks", "Compliance model and cross-validation",
                              "The run", "Digital twin results"}) {
    EXPECT_NE(html.find(section), std::string::npos) << section;
  }
  EXPECT_TRUE(std::regex_search(html, std::regex("[0-9a-f]{64}"))) << "SHA-256 hashes of the inputs";

  const std::string flags = " --headless --no-sandbox --disable-gpu --hide-scrollbars --virtual-time-budget=10000 ";
  const std::string url = "file://" + page.string();
  const auto dom = dir.path() / "dom.html", png = dir.path() / "page.png";
  ASSERT_EQ(std::system((chromium + flags + "--dump-dom '" + url + "' >'" + dom.string() + "' 2>/dev/null").c_str()), 0);
  const std::string loaded = read_text(dom);
  const std::string expected = "figures loaded: " + std::to_string(figures) + "/" + std::to_string(figures);
  EXPECT_NE(loaded.find(expected), std::string::npos)
      << "the page's own check: " << loaded.substr(loaded.find("report-status"), 200);
  ASSERT_EQ(std::system((chromium + flags + "--window-size=1200,2400 --screenshot='" + png.string() + "' '" + url +
                         "' >/dev/null 2>&1").c_str()),
            0);
  const cv::Mat image = cv::imread(png.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty()) << "no screenshot";
  EXPECT_EQ(image.cols, 1200);
  EXPECT_EQ(image.rows, 2400);
  cv::Mat gray;
  cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  cv::Scalar mean, stddev;
  cv::meanStdDev(gray, mean, stddev);
  const double ink = static_cast<double>(cv::countNonZero(gray < 200)) / static_cast<double>(gray.total());
  EXPECT_GT(stddev[0], 20.0) << "a blank page";
  EXPECT_GT(ink, 0.01) << "almost nothing drawn";
  // Colour: the heat map of the compliance figure (first figure, on the first screen) is not grey.
  cv::Mat hsv;
  cv::cvtColor(image, hsv, cv::COLOR_BGR2HSV);
  std::vector<cv::Mat> channels;
  cv::split(hsv, channels);
  EXPECT_GT(cv::countNonZero(channels[1] > 100), 5000) << "no coloured figure on screen";
}

}  // namespace
}  // namespace stiffpath::test
