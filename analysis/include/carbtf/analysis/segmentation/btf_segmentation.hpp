// Segmentation of a BTF's light x view space into subspaces (paper Sec. III, docs/design.md 4.1): K-means on
// the Lab cumulative-histogram feature of every image. Also measures the eigenvalue spectrum of the
// BTF space (paper Fig. 4): the eigenvalues of the covariance of all images, each reduced to a
// thumbnail of `spectrum_thumbnail`^2 linear RGB texels (box filter) to keep it a second's work.
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"

namespace carbtf {

struct SegmentationOptions {
  std::uint32_t clusters = 20;  // K, 1..255
  std::uint32_t bins = 32;      // per Lab channel
  std::uint64_t seed = 1;
  std::uint32_t max_feature_pixels = 16384;  // the feature samples every stride-th pixel to stay below this
  std::uint32_t spectrum_thumbnail = 16;
  unsigned threads = 0;
  bool progress = true;
};

struct Segmentation {
  std::uint32_t lights = 0;
  std::uint32_t views = 0;
  std::vector<std::uint8_t> index;         // lights * views, [light * views + view]
  std::vector<LightView> representatives;  // per subspace: the member nearest its centroid
  std::vector<std::uint32_t> sizes;        // measured images per subspace
  std::vector<double> eigenvalues;         // of the BTF space, descending
  double inertia = 0.0;
  std::uint32_t iterations = 0;
};

// Missing pairs of a partial dataset take the subspace of the nearest present pair (sum of the light
// and view angles). Throws std::invalid_argument for a dataset without images or a K outside 1..255.
Segmentation segment_btf(const BtfDataset& dataset, const SegmentationOptions& options);

}  // namespace carbtf
