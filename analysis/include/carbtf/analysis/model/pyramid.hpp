// The Gaussian-Laplacian pyramid (Burt & Adelson) a subspace band is split into (docs/design.md 4.3).
// reduce: blur with the binomial kernel [1 4 6 4 1] / 16 in each direction, keep every second sample
// (a size n becomes ceil(n / 2)). expand: the transpose, upsample by zero insertion and blur with twice
// the kernel, to a requested size. Borders are mirrored (whole-sample symmetric), which suits measured
// images that do not wrap around. Level k of a pyramid of L levels is the Laplacian G_k - expand(G_k+1)
// for k < L - 1 and the Gaussian G_{L-1} at the top, so collapse() restores the image up to rounding.
#pragma once

#include <vector>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

Plane reduce_plane(const Plane& fine);
Plane expand_plane(const Plane& coarse, Eigen::Index rows, Eigen::Index cols);

// levels >= 1; level 0 is the finest. A plane too small to halve stops the pyramid early.
std::vector<Plane> build_laplacian_pyramid(const Plane& image, int levels);
Plane collapse_pyramid(const std::vector<Plane>& pyramid);

}  // namespace carbtf
