// The median of a sample, for the figures and robust fits that need one.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace trackbed {

/// The median of `values` (the mean of the two middle values for an even count); 0 for
/// none. Takes the values by copy: it reorders them.
inline double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  double m = *mid;
  if (values.size() % 2 == 0) m = 0.5 * (m + *std::max_element(values.begin(), mid));
  return m;
}

}  // namespace trackbed
