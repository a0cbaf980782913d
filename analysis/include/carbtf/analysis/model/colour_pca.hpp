// Spectral decorrelation of a subspace image (paper Sec. IV, docs/design.md 4.3): the channels' mean and
// the eigenvectors of their covariance, so that band = basis^T (colour - mean) gives uncorrelated
// mono-spectral bands and colour = mean + basis * band restores the image. Works for any channel count
// (3 for RGB, N for multispectral). Bands are ordered by decreasing variance.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

struct ColourPca {
  Eigen::VectorXd mean;       // channels
  Eigen::MatrixXd basis;      // channels x channels, orthonormal columns
  Eigen::VectorXd variances;  // per band, decreasing
};

// `channels` planes of equal size. Throws std::invalid_argument on an empty or mismatched input.
ColourPca fit_colour_pca(const std::vector<Plane>& channels);
std::vector<Plane> to_bands(const ColourPca& pca, const std::vector<Plane>& channels);
std::vector<Plane> from_bands(const ColourPca& pca, const std::vector<Plane>& bands);

}  // namespace carbtf
