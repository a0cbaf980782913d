// The fidelity of synthesized subspace images alone (the fidelity column of `carbtf bench synth`): the
// calibrated rel of the texture measure (texture_references.hpp) of each subspace image against the
// measured image of its representative pair, the image its model was fitted to. The model image is the
// subspace image times the enlarged relief tone and relit range map (apply_relief): the render pass at
// the pair's own directions without parallax or interpolation, so the figure follows the synthesis
// alone; `carbtf fidelity` scores the whole render pass.
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/quality/texture_references.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/synthesis/synthesis_request.hpp"

namespace carbtf {

struct SubspaceFidelity {
  std::uint32_t pairs = 0;  // subspace images scored (0: none)
  double mean_rel = 0.0, worst_rel = 0.0, mean_gaussian_rel = 0.0;
};

// The measured image (linear RGB) of each subspace's representative pair, in subspace order. Throws
// std::invalid_argument naming the dataset and the pair when one is missing.
std::vector<RgbField> representative_images(const BtfDataset& dataset, const Material& material);

// Scores every 3-channel subspace image `images` holds against `measured` (representative_images()).
SubspaceFidelity subspace_fidelity(const Material& material, const SynthesizedImages& images,
                                   const std::vector<RgbField>& measured);

}  // namespace carbtf
