#include "carbtf/analysis/range/relief_band_limit.hpp"

#include <array>

namespace carbtf {
namespace {

constexpr std::array<double, 5> kBandLimitTaps = {-1.0 / 16.0, 4.0 / 16.0, 10.0 / 16.0, 4.0 / 16.0,
                                                  -1.0 / 16.0};

// One periodic pass of the taps along rows (`along_rows`) or down columns.
Plane filter_pass(const Plane& in, bool along_rows) {
  const Eigen::Index rows = in.rows(), cols = in.cols();
  Plane out(rows, cols);
  for (Eigen::Index r = 0; r < rows; ++r) {
    for (Eigen::Index c = 0; c < cols; ++c) {
      double sum = 0.0;
      for (Eigen::Index t = -2; t <= 2; ++t) {
        const double tap = kBandLimitTaps[static_cast<std::size_t>(t + 2)];
        sum += along_rows ? tap * in(r, ((c + t) % cols + cols) % cols)
                          : tap * in(((r + t) % rows + rows) % rows, c);
      }
      out(r, c) = sum;
    }
  }
  return out;
}

}  // namespace

Plane band_limit_relief(const Plane& range_map) {
  if (range_map.size() == 0) return range_map;
  const Plane filtered = filter_pass(filter_pass(range_map, true), false);
  return range_map + kReliefBandLimitShare * (filtered - range_map);
}

}  // namespace carbtf
