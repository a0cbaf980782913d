// One channel of an image as the model code sees it: double precision, row-major, (row, col) indexed,
// row 0 at the top. Analysis works in double so that decompositions reconstruct to rounding error.
#pragma once

#include <Eigen/Core>

namespace carbtf {

using Plane = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace carbtf
