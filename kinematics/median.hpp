#pragma once
// The station's medians, written once: the summaries across cells, the robust outlier and noise
// estimates, and the running median that steadies a yaw rate.

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

namespace avk::kinematics {

// The element at size / 2 in sorted order: the median of an odd count, the upper of the two
// middle values of an even one. Reorders `values`, which must not be empty.
double upper_median(std::vector<double>& values);

// Median of the finite values (the mean of the two middle ones for an even count); empty when
// there are none.
std::optional<double> median_of(std::vector<double> values);

// Median across items of what `value` gives each (an empty optional: the item does not count).
template <class Items, class Value>
std::optional<double> median_over(const Items& items, Value value) {
  std::vector<double> v;
  for (const auto& item : items)
    if (const std::optional<double> x = value(item)) v.push_back(*x);
  return median_of(std::move(v));
}

// Median of three, infinities kept: a running median over a series that marks gaps with them.
inline double median3(double a, double b, double c) {
  return std::max(std::min(a, b), std::min(std::max(a, b), c));
}

}  // namespace avk::kinematics
