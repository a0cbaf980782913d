#include "carbtf/analysis/model/colour_pca.hpp"

#include <Eigen/Eigenvalues>
#include <stdexcept>

namespace carbtf {
namespace {

void check_planes(const std::vector<Plane>& planes, const char* what) {
  if (planes.empty()) throw std::invalid_argument(std::string(what) + ": no channels");
  for (const Plane& p : planes) {
    if (p.rows() != planes[0].rows() || p.cols() != planes[0].cols() || p.size() == 0) {
      throw std::invalid_argument(std::string(what) + ": channels differ in size or are empty");
    }
  }
}

}  // namespace

ColourPca fit_colour_pca(const std::vector<Plane>& channels) {
  check_planes(channels, "colour PCA");
  const auto count = static_cast<Eigen::Index>(channels.size());
  const double pixels = static_cast<double>(channels[0].size());
  ColourPca pca;
  pca.mean.resize(count);
  for (Eigen::Index c = 0; c < count; ++c) pca.mean(c) = channels[c].mean();
  Eigen::MatrixXd covariance(count, count);
  for (Eigen::Index i = 0; i < count; ++i) {
    for (Eigen::Index j = 0; j <= i; ++j) {
      const double value = ((channels[i] - pca.mean(i)) * (channels[j] - pca.mean(j))).sum() / pixels;
      covariance(i, j) = covariance(j, i) = value;
    }
  }
  // Symmetric eigen-decomposition: orthonormal eigenvectors even for repeated or zero eigenvalues
  // (grey or constant images), so the inverse is the transpose and never an explicit inverse.
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
  pca.basis = solver.eigenvectors().rowwise().reverse();
  pca.variances = solver.eigenvalues().reverse().cwiseMax(0.0);
  // A sign convention, so the same image always gives the same basis: the largest component positive.
  for (Eigen::Index c = 0; c < count; ++c) {
    Eigen::Index largest = 0;
    pca.basis.col(c).cwiseAbs().maxCoeff(&largest);
    if (pca.basis(largest, c) < 0.0) pca.basis.col(c) *= -1.0;
  }
  return pca;
}

std::vector<Plane> to_bands(const ColourPca& pca, const std::vector<Plane>& channels) {
  check_planes(channels, "colour PCA");
  std::vector<Plane> bands;
  for (Eigen::Index b = 0; b < pca.basis.cols(); ++b) {
    Plane band = Plane::Zero(channels[0].rows(), channels[0].cols());
    for (Eigen::Index c = 0; c < pca.basis.rows(); ++c) band += pca.basis(c, b) * (channels[c] - pca.mean(c));
    bands.push_back(std::move(band));
  }
  return bands;
}

std::vector<Plane> from_bands(const ColourPca& pca, const std::vector<Plane>& bands) {
  check_planes(bands, "colour PCA");
  std::vector<Plane> channels;
  for (Eigen::Index c = 0; c < pca.basis.rows(); ++c) {
    Plane channel = Plane::Constant(bands[0].rows(), bands[0].cols(), pca.mean(c));
    for (Eigen::Index b = 0; b < pca.basis.cols(); ++b) channel += pca.basis(c, b) * bands[b];
    channels.push_back(std::move(channel));
  }
  return channels;
}

}  // namespace carbtf
