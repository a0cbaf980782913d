// Loading measured BTFs. Every reader checks its input and throws InputError naming the file and the
// problem; none writes anything.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"

namespace carbtf {

struct BtfLoadOptions {
  unsigned threads = 0;  // decoding threads; 0: all hardware threads
  bool progress = true;  // progress bar on stderr when it is a terminal
};

// Loads whatever `path` is:
//   - a folder in the UBO2003 layout (flat, or per-view folders tvTTT_pvPPP), or a .zip of one;
//   - a manifest .csv (path,theta_i,phi_i,theta_v,phi_v in degrees) for any other direction set;
//   - a photometric-stereo folder: one that holds light_directions.txt (see read_photometric_stereo);
//   - a Bonn UBO2014 .btf file, DFMF or raw (see read_ubo2014_btf).
// Missing (light, view) pairs are allowed and reported in `warnings`.
BtfDataset load_btf(const std::filesystem::path& path, const BtfLoadOptions& options,
                    std::vector<std::string>& warnings);

// The UBO2003 folder reader on its own.
BtfDataset read_ubo2003_folder(const std::filesystem::path& folder, const BtfLoadOptions& options,
                               std::vector<std::string>& warnings);

// A manifest .csv: one line per image, `path,theta_i,phi_i,theta_v,phi_v`, angles in degrees, paths
// relative to the manifest; an optional header line "path,..."; lines starting with '#' are comments.
BtfDataset read_manifest(const std::filesystem::path& manifest, const BtfLoadOptions& options,
                         std::vector<std::string>& warnings);

// A photometric-stereo set as common benchmarks (DiLiGenT) ship it: N images of one view (the top)
// and light_directions.txt with one "x y z" line per image (x right, y up, z towards the camera).
// Optional: filenames.txt (the images in light order; otherwise the folder's images sorted by name,
// leaving out mask.* and normal*), light_intensities.txt (one "r g b" line per image; images are
// divided by it), mask.png (non-zero where the object is).
BtfDataset read_photometric_stereo(const std::filesystem::path& folder, const BtfLoadOptions& options,
                                   std::vector<std::string>& warnings);

// A Bonn UBO2014 .btf file (analysis/btf/ubo2014_format.hpp). DFMF files give a dataset that rebuilds
// each image on access from the factors (encoding `decoded`); raw (BDI) files are read into half-float
// images. Texels a sparse BDI does not store are 0 and outside the dataset's mask.
BtfDataset read_ubo2014_btf(const std::filesystem::path& path, const BtfLoadOptions& options,
                            std::vector<std::string>& warnings);

}  // namespace carbtf
