// Fixed-point decimal text of a double, correctly rounded: the joint files' number format.
#pragma once

#include <cstddef>
#include <cstdint>

namespace stiffpath::job {

//! Longest text write_fixed() writes: a sign, the 309 integer digits of the largest double, the point, 9 decimals.
inline constexpr std::size_t kMaxFixedChars = 1 + 309 + 1 + 9;

//! Writes `value` correctly rounded to `decimals` (0…9) places after the point, as printf("%.*f") would
//! (ties to even on the exact binary value), except that a negative value that rounds to zero is written
//! without its sign ("0.000", not "-0.000"); returns the end. `out` must hold kMaxFixedChars. Magnitudes
//! below 10⁹ (every joint-file cell in practice) take an exact 128-bit integer path, about 2.5× faster
//! than std::to_chars; larger and non-finite values go to std::to_chars.
char* write_fixed(char* out, double value, int decimals) noexcept;

}  // namespace stiffpath::job
