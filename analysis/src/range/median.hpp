// The median of a sample, shared by the range map's robust fits (photometric stereo's outlier
// rejection, the normal integration's weights).
#pragma once

#include <algorithm>
#include <vector>

namespace carbtf::detail {

// The upper median (the middle element of an even count); 0 for an empty sample.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace carbtf::detail
