// The median of a set of numbers, with the rule for an even count said by the caller: one value, not four copies.
#pragma once

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <span>
#include <vector>

namespace stiffpath::core {

//! σ of a normal distribution per median absolute deviation (1/Φ⁻¹(3/4)): a robust σ is kMadToSigma · MAD.
inline constexpr double kMadToSigma = 1.4826;

//! Which value a median of an even number of values is.
enum class MedianRule {
  //! The mean of the two middle values: the textbook median, for statistics that are reported.
  mean_of_middles,
  //! The larger of the two middle values (element n/2 of the sorted values): always one of the values,
  //! found by one partial sort; for robust estimates inside an algorithm, where the half-sample
  //! difference does not matter and the speed does.
  upper_middle,
  //! The smaller of the two middle values (element (n−1)/2 of the sorted values).
  lower_middle,
};

//! The median of `values` by `rule`, reordering them in place (std::nth_element: O(n), no copy); 0 for none.
template <class T>
[[nodiscard]] double median_in_place(std::span<T> values, MedianRule rule) {
  const std::size_t n = values.size();
  if (n == 0) return 0.0;
  const auto begin = values.begin();
  const std::size_t upper = n / 2, lower = (n - 1) / 2;
  const std::size_t at = rule == MedianRule::lower_middle ? lower : upper;
  std::nth_element(begin, begin + static_cast<std::ptrdiff_t>(at), values.end());
  const double middle = static_cast<double>(values[at]);
  if (rule != MedianRule::mean_of_middles || n % 2 == 1) return middle;
  // The lower middle is the largest of the values before the upper one (nth_element put them there).
  const double below = static_cast<double>(*std::max_element(begin, begin + static_cast<std::ptrdiff_t>(upper)));
  return 0.5 * (below + middle);
}

//! The median of a copy of `values` by `rule`; 0 for none.
template <class T>
[[nodiscard]] double median(std::vector<T> values, MedianRule rule) {
  return median_in_place(std::span<T>(values), rule);
}

}  // namespace stiffpath::core
