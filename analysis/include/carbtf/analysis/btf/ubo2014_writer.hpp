// Writes a dataset as a Bonn UBO2014 .btf file (analysis/btf/ubo2014_format.hpp), in either layout: for
// the reader's tests and for `carbtf bench data`'s synthetic files.
#pragma once

#include <cstdint>
#include <filesystem>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/btf/ubo2014_format.hpp"

namespace carbtf {

struct Ubo2014WriteOptions {
  ubo2014::Layout layout = ubo2014::Layout::dfmf;
  // DFMF: the components per channel. 0 writes one per light/view pair, U the identity and S x V the
  // data itself: exact wherever the values fit the scalars. Otherwise a rank-`components` factorisation
  // (a seeded randomised SVD, two passes over the images).
  std::uint32_t components = 0;
  ubo2014::ColourModel colour_model = ubo2014::ColourModel::rgb;  // DFMF: rgb, yuv or pca
  std::uint8_t scalar_bytes = 2;                                  // DFMF: 2 (half) or 4 (float)
  bool cosine_in_data = true;              // false: the values are divided by cos(theta) of the light, flag 0
  std::uint32_t scan_lines_per_chunk = 1;  // BDI
  bool sparse = false;                     // BDI: store only the texels of the dataset's mask (compression 2)
  std::uint64_t seed = 1;
};

// Throws std::runtime_error when the file cannot be written, std::invalid_argument on options the
// format cannot hold (a missing pair, a colour model carbtf does not write).
void write_ubo2014_btf(const std::filesystem::path& path, const BtfDataset& dataset,
                       const Ubo2014WriteOptions& options);

}  // namespace carbtf
