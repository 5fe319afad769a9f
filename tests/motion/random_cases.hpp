// Test helper: the number of seeded random cases, from STIFFPATH_RANDOM_CASES (default given per test).
#pragma once

#include <cstdlib>
#include <string>

namespace stiffpath::test {

//! Random-sweep size: STIFFPATH_RANDOM_CASES if set (e.g. 100000 for a long soak), else `fallback`.
inline int random_cases(int fallback) {
  if (const char* env = std::getenv("STIFFPATH_RANDOM_CASES")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  return fallback;
}

}  // namespace stiffpath::test
