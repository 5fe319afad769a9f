// Fixed-point decimal formatting of doubles for joint CSV files, without printf or allocation.
#pragma once

#include <string>

namespace stiffpath::job {

//! Longest text write_fixed() produces: sign, 19 digits, the point (|value|·10^decimals < 9.2e18).
inline constexpr int kMaxFixedChars = 21;

//! Writes `value` with `decimals` (0–9) digits after the point at `out` and returns the end: the
//! value times 10^decimals rounded half away from zero (llround), no exponent, no "-0". `out` must
//! have room for kMaxFixedChars characters; |value|·10^decimals must stay below 9.2e18.
char* write_fixed(char* out, double value, int decimals) noexcept;

//! The same, appended to a string. About 10× faster than printf("%.*f") for the magnitudes in a
//! joint file.
void append_fixed(std::string& out, double value, int decimals);

}  // namespace stiffpath::job
