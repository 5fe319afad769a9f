// Windowed darkness sums, core darkness, flank medians and running means of cross-sections.
#include "cross_section.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "stiffpath/core/median.hpp"

namespace stiffpath::vision::detail {

WindowSums window_sums(const SectionFrame& frame, int a, double lo, double hi, const Paper& paper) {
  WindowSums s;
  const int first = static_cast<int>(std::floor(lo)), last = static_cast<int>(std::floor(hi));
  const int nb = frame.size_b();
  if (first < 0 || last >= nb) s.clipped = true;
  for (int b = std::max(first, 0); b <= std::min(last, nb - 1); ++b) {
    const double f = std::min(hi, b + 1.0) - std::max(lo, static_cast<double>(b));
    if (f <= 0.0) continue;
    const double centre = b + 0.5;
    const double d = 1.0 - frame.at(a, b) / paper(centre);
    s.mass += f * d;
    s.moment += f * d * centre;
    s.moment2 += f * d * centre * centre;
  }
  return s;
}

double core_darkness(const SectionFrame& frame, int a, double b, const Paper& paper) {
  const int pb = std::clamp(static_cast<int>(std::floor(b)), 0, frame.size_b() - 1);
  return 1.0 - frame.at(a, pb) / paper(pb + 0.5);
}

std::optional<double> flank_median(const SectionFrame& frame, int a, int lo, int hi) {
  float values[64];
  int n = 0;
  for (int b = std::max(lo, 0); b < std::min(hi, frame.size_b()) && n < 64; ++b) values[n++] = frame.at(a, b);
  if (n == 0) return std::nullopt;
  // A few pixels (cut short at the image's edge to an even count): the mean of the two middle ones.
  return core::median_in_place(std::span<float>(values, static_cast<std::size_t>(n)), core::MedianRule::mean_of_middles);
}

std::vector<std::optional<double>> running_mean(const std::vector<std::optional<double>>& v, int half_window) {
  const int n = static_cast<int>(v.size());
  std::vector<double> sum(static_cast<std::size_t>(n) + 1, 0.0);
  std::vector<int> count(static_cast<std::size_t>(n) + 1, 0);
  for (int i = 0; i < n; ++i) {
    sum[i + 1] = sum[i] + v[i].value_or(0.0);
    count[i + 1] = count[i] + (v[i] ? 1 : 0);
  }
  std::vector<std::optional<double>> out(v.size());
  for (int i = 0; i < n; ++i) {
    const int lo = std::max(0, i - half_window), hi = std::min(n, i + half_window + 1);
    const int c = count[hi] - count[lo];
    if (c > 0) out[i] = (sum[hi] - sum[lo]) / c;
  }
  return out;
}

double local_slope(const SideSections& side, int a) {
  double n = 0, sa = 0, sb = 0, saa = 0, sab = 0;
  const int half = side.tuning->slope_half_window_sections;
  for (int j = std::max(side.body_first, a - half); j <= std::min(side.body_last, a + half); ++j) {
    const Section& s = side.at(j);
    if (!s.body || s.rejected) continue;
    const double x = j - a;
    n += 1, sa += x, sb += s.centre, saa += x * x, sab += x * s.centre;
  }
  const double det = n * saa - sa * sa;
  return n >= 3 && det > 0 ? (n * sab - sa * sb) / det : 0.0;
}

}  // namespace stiffpath::vision::detail
