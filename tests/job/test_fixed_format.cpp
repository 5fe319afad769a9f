// write_fixed against glibc's printf("%.*f"): random magnitudes, every decimal count, exact binary ties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "stiffpath/job/fixed_format.hpp"

namespace stiffpath::job {
namespace {

std::string fixed(double v, int d) {
  char out[kMaxFixedChars + 1];
  *write_fixed(out, v, d) = '\0';
  return out;
}

// printf's text, without the sign of a negative value that rounds to zero.
std::string reference(double v, int d) {
  char text[400];
  std::snprintf(text, sizeof text, "%.*f", d, v);
  const std::size_t n = std::strlen(text);
  if (text[0] == '-' && std::all_of(text + 1, text + n, [](char c) { return c == '0' || c == '.'; })) return text + 1;
  return text;
}

TEST(FixedFormat, EqualsPrintfOnRandomValuesAndExactTies) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 10), decimals(0, 9);
  for (int i = 0; i < 300000; ++i) {
    // Every fourth value a short binary fraction: k/2^s lands exactly halfway between two outputs often.
    const double v = i % 4 == 0 ? std::ldexp(std::floor(u(rng) * 1e6), -(i % 41)) : u(rng) * std::pow(10.0, exponent(rng));
    const int d = decimals(rng);
    ASSERT_EQ(fixed(v, d), reference(v, d)) << v << " at " << d;
  }
  EXPECT_EQ(fixed(1.0 / 128, 6), "0.007812");   // 7812.5 → even
  EXPECT_EQ(fixed(3.0 / 128, 6), "0.023438");   // 23437.5 → even
  EXPECT_EQ(fixed(0.5, 0), "0");
  EXPECT_EQ(fixed(1.5, 0), "2");
  EXPECT_EQ(fixed(-0.0000004, 6), "0.000000");  // no "-0"
  EXPECT_EQ(fixed(-2.5, 0), "-2");
}

TEST(FixedFormat, LargeAndNonFiniteValuesTakeTheGeneralPath) {
  for (double v : {1e9, -1e9, 999999999.99999988, 1.7976931348623157e308, 1e15 + 0.5, 4.9e-324}) {
    for (int d : {0, 4, 9}) EXPECT_EQ(fixed(v, d), reference(v, d)) << v << " at " << d;
  }
  EXPECT_EQ(fixed(std::numeric_limits<double>::infinity(), 3), "inf");
  EXPECT_EQ(fixed(std::numeric_limits<double>::quiet_NaN(), 3), "nan");
}

}  // namespace
}  // namespace stiffpath::job
