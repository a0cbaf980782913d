#include "carbtf/analysis/model/pyramid.hpp"

#include <array>
#include <stdexcept>

namespace carbtf {
namespace {

constexpr std::array<double, 5> kBinomial{1.0 / 16, 4.0 / 16, 6.0 / 16, 4.0 / 16, 1.0 / 16};

// Whole-sample symmetric reflection: -1 -> 1, n -> n - 2.
Eigen::Index mirror(Eigen::Index i, Eigen::Index n) {
  if (n == 1) return 0;
  const Eigen::Index period = 2 * (n - 1);
  i %= period;
  if (i < 0) i += period;
  return i < n ? i : period - i;
}

// Blurs along rows (axis 1) or columns (axis 0) and keeps every second sample.
Plane reduce_axis(const Plane& in, int axis) {
  const Eigen::Index n = axis == 1 ? in.cols() : in.rows();
  const Eigen::Index half = (n + 1) / 2;
  Plane out(axis == 1 ? in.rows() : half, axis == 1 ? half : in.cols());
  for (Eigen::Index r = 0; r < out.rows(); ++r) {
    for (Eigen::Index c = 0; c < out.cols(); ++c) {
      double sum = 0.0;
      for (int k = -2; k <= 2; ++k) {
        const double w = kBinomial[k + 2];
        sum += axis == 1 ? w * in(r, mirror(2 * c + k, n)) : w * in(mirror(2 * r + k, n), c);
      }
      out(r, c) = sum;
    }
  }
  return out;
}

// The transpose of reduce_axis: fine sample i gathers coarse j with weight 2 * kernel(i - 2j), the
// coarse samples mirrored the same way the fine ones were.
Plane expand_axis(const Plane& in, int axis, Eigen::Index size) {
  const Eigen::Index n = axis == 1 ? in.cols() : in.rows();
  Plane out(axis == 1 ? in.rows() : size, axis == 1 ? size : in.cols());
  for (Eigen::Index r = 0; r < out.rows(); ++r) {
    for (Eigen::Index c = 0; c < out.cols(); ++c) {
      const Eigen::Index i = axis == 1 ? c : r;
      double sum = 0.0;
      for (int k = -2; k <= 2; ++k) {
        if ((i - k) % 2 != 0) continue;
        const Eigen::Index j = mirror((i - k) / 2, n);
        const double w = 2.0 * kBinomial[k + 2];
        sum += axis == 1 ? w * in(r, j) : w * in(j, c);
      }
      out(r, c) = sum;
    }
  }
  return out;
}

}  // namespace

Plane reduce_plane(const Plane& fine) {
  return reduce_axis(reduce_axis(fine, 1), 0);
}

Plane expand_plane(const Plane& coarse, Eigen::Index rows, Eigen::Index cols) {
  return expand_axis(expand_axis(coarse, 1, cols), 0, rows);
}

std::vector<Plane> build_laplacian_pyramid(const Plane& image, int levels) {
  if (levels < 1) throw std::invalid_argument("a pyramid needs at least one level");
  if (image.size() == 0) throw std::invalid_argument("cannot build a pyramid of an empty image");
  std::vector<Plane> pyramid;
  Plane gaussian = image;
  for (int level = 0; level + 1 < levels && gaussian.rows() >= 2 && gaussian.cols() >= 2; ++level) {
    Plane coarser = reduce_plane(gaussian);
    pyramid.push_back(gaussian - expand_plane(coarser, gaussian.rows(), gaussian.cols()));
    gaussian = std::move(coarser);
  }
  pyramid.push_back(std::move(gaussian));
  return pyramid;
}

Plane collapse_pyramid(const std::vector<Plane>& pyramid) {
  if (pyramid.empty()) throw std::invalid_argument("cannot collapse an empty pyramid");
  Plane image = pyramid.back();
  for (auto level = pyramid.rbegin() + 1; level != pyramid.rend(); ++level) {
    image = *level + expand_plane(image, level->rows(), level->cols());
  }
  return image;
}

}  // namespace carbtf
