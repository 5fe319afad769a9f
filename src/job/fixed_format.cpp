// write_fixed / append_fixed: scaled integer rounding, then digits two at a time from a table.
#include "stiffpath/job/fixed_format.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace stiffpath::job {

namespace {
constexpr std::array<double, 10> kScale = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
constexpr std::array<std::uint64_t, 10> kPow10 = {1ULL,         10ULL,         100ULL,         1000ULL,
                                                  10000ULL,     100000ULL,     1000000ULL,     10000000ULL,
                                                  100000000ULL, 1000000000ULL};

// "00", "01", … "99": the two digits of every number below 100.
constexpr std::array<char, 200> two_digit_table() {
  std::array<char, 200> t{};
  for (int i = 0; i < 100; ++i) {
    t[static_cast<std::size_t>(2 * i)] = static_cast<char>('0' + i / 10);
    t[static_cast<std::size_t>(2 * i + 1)] = static_cast<char>('0' + i % 10);
  }
  return t;
}
constexpr std::array<char, 200> kTwoDigits = two_digit_table();

// Exactly `count` digits of `value` (< 10^count), zero-padded, ending at `end`.
void write_padded(char* end, std::uint64_t value, int count) noexcept {
  for (; count >= 2; count -= 2) {
    end -= 2;
    std::memcpy(end, &kTwoDigits[static_cast<std::size_t>(2 * (value % 100))], 2);
    value /= 100;
  }
  if (count == 1) *--end = static_cast<char>('0' + value);
}
}  // namespace

char* write_fixed(char* out, double value, int decimals) noexcept {
  const auto d = static_cast<std::size_t>(decimals);
  const long long scaled = std::llround(value * kScale[d]);
  const std::uint64_t magnitude =
      scaled < 0 ? 0ULL - static_cast<std::uint64_t>(scaled) : static_cast<std::uint64_t>(scaled);
  if (scaled < 0) *out++ = '-';
  out = std::to_chars(out, out + 20, magnitude / kPow10[d]).ptr;  // the integer part, "0" at least
  if (decimals == 0) return out;
  *out++ = '.';
  write_padded(out + decimals, magnitude % kPow10[d], decimals);
  return out + decimals;
}

void append_fixed(std::string& out, double value, int decimals) {
  char text[kMaxFixedChars];
  out.append(text, write_fixed(text, value, decimals));
}

}  // namespace stiffpath::job
