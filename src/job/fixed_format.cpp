// Fixed-point decimal text of a double, correctly rounded, by exact integer arithmetic where it can.
#include "stiffpath/job/fixed_format.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

namespace stiffpath::job {
namespace {

__extension__ using Uint128 = unsigned __int128;  // GCC and Clang on 64-bit targets

constexpr std::uint64_t kPow10[10] = {1,         10,         100,         1000,         10000,
                                      100000,    1000000,    10000000,    100000000,    1000000000};

// |value|·10^decimals rounded to the nearest integer, ties to even, computed exactly: with
// |value| = m·2^−s (m < 2^53 an integer), m·10^decimals < 2^83 fits in 128 bits, and the bits shifted
// out decide the rounding. For |value| < 10⁹ and decimals ≤ 9 (the result stays below 10¹⁸).
std::uint64_t scaled_round(double magnitude, int decimals) noexcept {
  int exponent = 0;
  const double fraction = std::frexp(magnitude, &exponent);  // magnitude = fraction·2^exponent, fraction ∈ [0.5, 1)
  const auto m = static_cast<std::uint64_t>(std::ldexp(fraction, 53));
  const int shift = 53 - exponent;  // > 23 for magnitudes below 10⁹
  const Uint128 n = static_cast<Uint128>(m) * kPow10[decimals];
  if (shift > 100) return 0;  // n < 2^83 < half of 2^shift
  auto q = static_cast<std::uint64_t>(n >> shift);
  const Uint128 rest = n & ((static_cast<Uint128>(1) << shift) - 1);
  const Uint128 half = static_cast<Uint128>(1) << (shift - 1);
  if (rest > half || (rest == half && (q & 1) != 0)) ++q;
  return q;
}

}  // namespace

char* write_fixed(char* p, double value, int decimals) noexcept {
  const double magnitude = std::fabs(value);
  if (magnitude < 1e9 && decimals >= 0 && decimals <= 9) {
    const std::uint64_t q = scaled_round(magnitude, decimals);
    if (q != 0 && std::signbit(value)) *p++ = '-';
    const std::uint64_t unit = kPow10[decimals];
    p = std::to_chars(p, p + 20, q / unit).ptr;
    if (decimals > 0) {
      *p++ = '.';
      std::uint64_t frac = q % unit;
      for (int k = decimals - 1; k >= 0; --k) {
        p[k] = static_cast<char>('0' + frac % 10);
        frac /= 10;
      }
      p += decimals;
    }
    return p;
  }
  char* end = std::to_chars(p, p + kMaxFixedChars, value, std::chars_format::fixed, decimals).ptr;
  if (std::signbit(value) && value > -1.0 && std::all_of(p + 1, end, [](char c) { return c == '0' || c == '.'; })) {
    std::memmove(p, p + 1, static_cast<std::size_t>(end - p - 1));
    --end;
  }
  return end;
}

}  // namespace stiffpath::job
