// Internal to the readers: images to decode, wherever their bytes live, and the shared step that
// decodes them (in parallel) into a BtfDataset with every consistency check.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"

namespace carbtf::detail {

struct ImageSource {
  std::string name;                              // shown in errors: a path, or "archive.zip:entry"
  std::function<std::vector<std::byte>()> read;  // must be safe to call from worker threads
  LightView pair;
};

// Optional step between decoding and storing (e.g. dividing by per-light intensities); runs on
// worker threads.
using ImageAdjustment = std::function<void(const ImageSource&, RgbImage&)>;

// Decodes every source into a dataset over `lights` x `views`. Throws InputError on the first bad
// image (mixed sizes or encodings included). Pairs without a source are reported in `warnings`.
BtfDataset decode_sources(const std::vector<ImageSource>& sources, std::vector<Direction> lights,
                          std::vector<Direction> views, std::string description,
                          const BtfLoadOptions& options, std::vector<std::string>& warnings,
                          const ImageAdjustment& adjust = {});

// "theta 30, phi 120" with integer degrees, for messages.
std::string describe_direction(const Direction& d);

}  // namespace carbtf::detail
