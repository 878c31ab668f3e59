#include "kinematics/median.hpp"

#include <cmath>
#include <cstddef>

namespace avk::kinematics {

double upper_median(std::vector<double>& values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

std::optional<double> median_of(std::vector<double> values) {
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  if (values.empty()) return std::nullopt;
  const double upper = upper_median(values);
  if (values.size() % 2 == 1) return upper;
  // nth_element left the lower half before the middle: its largest is the other middle value.
  const double lower = *std::max_element(
      values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2));
  return 0.5 * (lower + upper);
}

}  // namespace avk::kinematics
