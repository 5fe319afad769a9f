// core::median against a full sort, for each rule of an even count; in place it reorders, by copy it does not.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "stiffpath/core/median.hpp"

namespace stiffpath::core {
namespace {

TEST(Median, SmallCasesByRule) {
  EXPECT_EQ(median(std::vector<double>{}, MedianRule::mean_of_middles), 0.0);
  EXPECT_EQ(median(std::vector<double>{3.0}, MedianRule::lower_middle), 3.0);
  EXPECT_EQ(median(std::vector<double>{5, 1, 3}, MedianRule::mean_of_middles), 3.0);
  EXPECT_EQ(median(std::vector<double>{4, 1, 3, 2}, MedianRule::mean_of_middles), 2.5);
  EXPECT_EQ(median(std::vector<double>{4, 1, 3, 2}, MedianRule::upper_middle), 3.0);
  EXPECT_EQ(median(std::vector<double>{4, 1, 3, 2}, MedianRule::lower_middle), 2.0);
  EXPECT_EQ(median(std::vector<float>{7.5f, -1.0f}, MedianRule::mean_of_middles), 3.25);
}

// Oracle: the sorted values' middle element(s), for random sets of odd and even size with repeated values.
TEST(Median, EqualsTheSortedMiddleForRandomSets) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<double> v(1 + rng() % 60);
    for (auto& x : v) x = static_cast<double>(static_cast<int>(rng() % 25)) - 12.0;
    std::vector<double> sorted = v;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = v.size();
    const double lo = sorted[(n - 1) / 2], hi = sorted[n / 2];
    EXPECT_EQ(median(v, MedianRule::lower_middle), lo);
    EXPECT_EQ(median(v, MedianRule::upper_middle), hi);
    EXPECT_EQ(median(v, MedianRule::mean_of_middles), 0.5 * (lo + hi));
    std::vector<double> copy = v;
    EXPECT_EQ(median_in_place(std::span<double>(copy), MedianRule::mean_of_middles), 0.5 * (lo + hi));
    std::sort(copy.begin(), copy.end());
    EXPECT_EQ(copy, sorted);  // reordered, nothing lost
  }
}

}  // namespace
}  // namespace stiffpath::core
