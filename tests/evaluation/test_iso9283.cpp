// Tests of ISO 9283 path accuracy and repeatability on hand-built attained paths.
#include <gtest/gtest.h>

#include "stiffpath/core/error.hpp"
#include "stiffpath/evaluation/iso9283.hpp"

namespace stiffpath::evaluation {
namespace {

std::vector<Point2> shifted(const std::vector<Point2>& path, const Point2& by) {
  std::vector<Point2> out;
  for (const auto& p : path) out.push_back(p + by);
  return out;
}

TEST(Iso9283, ConstantOffsetIsTheAccuracyAndSpreadTheRepeatability) {
  const std::vector<Point2> command{{0, 0}, {0.1, 0}, {0.1, 0.05}};
  const auto a = iso9283_path_accuracy(command, {shifted(command, {0, 1e-4})}, 50);
  // On the first leg the normal offset is 0.1 mm; on the second leg (along y) the y shift runs along it.
  EXPECT_NEAR(a.accuracy_m, 1e-4, 1e-12);
  EXPECT_EQ(a.repeatability_m, 0.0);
  EXPECT_EQ(a.planes_used, 50u);

  const auto two = iso9283_path_accuracy(command, {shifted(command, {0, 5e-5}), shifted(command, {0, -5e-5})}, 40);
  // On the first leg the barycentre is on the command; each run is 0.05 mm from it with no spread.
  EXPECT_NEAR(two.repeatability_m, 5e-5, 1e-12);
  EXPECT_LT(two.accuracy_m, 1e-12);
}

TEST(Iso9283, ThreeRunsRepeatabilityHandChecked) {
  const std::vector<Point2> command{{0, 0}, {0.1, 0}};
  const std::vector<std::vector<Point2>> runs{shifted(command, {0, 1e-4}), shifted(command, {0, 0}),
                                              shifted(command, {0, -2e-4})};
  const auto r = iso9283_path_accuracy(command, runs, 10);
  // Barycentre at y = −1/3·1e-4; distances 4/3, 1/3, 5/3 (×1e-4): mean 10/9, sd √(1/3)·… computed below.
  const double d[3] = {4e-4 / 3, 1e-4 / 3, 5e-4 / 3};
  const double mean = (d[0] + d[1] + d[2]) / 3;
  double sq = 0;
  for (double x : d) sq += (x - mean) * (x - mean);
  EXPECT_NEAR(r.accuracy_m, 1e-4 / 3, 1e-12);
  EXPECT_NEAR(r.repeatability_m, mean + 3 * std::sqrt(sq / 2), 1e-12);
}

TEST(Iso9283, RefusesUnusableInput) {
  const std::vector<Point2> command{{0, 0}, {0.1, 0}};
  EXPECT_THROW(iso9283_path_accuracy(command, {}), Error);
  EXPECT_THROW(iso9283_path_accuracy(std::vector<Point2>{{0, 0}}, {command}), Error);
  const std::vector<Point2> elsewhere{{0.5, 0}, {0.6, 0}};  // never crosses the normals of the command
  EXPECT_THROW(iso9283_path_accuracy(command, {elsewhere}), Error);
}

}  // namespace
}  // namespace stiffpath::evaluation
