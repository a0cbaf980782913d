// Pair gains (Material::pair_gains, issue 13): per measured (light, view) pair, the colour gains that
// give the model's render of the pair its measurement's mean CIE L*a*b* colour. A subspace image stands
// for every pair of its cluster, which group by texture, not by mean colour: without gains a pair keeps
// its representative's colour, and the calibrated fidelity's colour group (the Lab mean's delta E) was
// 0.6-2.7 delta E off on the sample materials where the half-image floor is about 0.4.
//
// Matched in Lab, not in linear RGB: the eye (and the fidelity measure) averages perceived colour, and
// a model whose contrast differs from the measurement's has another Lab mean at the same linear mean.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/model/plane.hpp"
#include "carbtf/analysis/model/relief_specular.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

// The relief the render pass composes with each subspace image: the range map and what follows it.
struct PairGainRelief {
  const Plane& range_map;           // texel units
  std::span<const Plane> tone;      // the stored tone's planes: none, one grey or R, G and B
  std::span<const float> horizons;  // the range map's horizons, empty without cast shadows
  SpecularLobe specular = {};       // the highlights the render adds, which no gain scales
};

// Gain codes for `material` (its subspace models fitted, lights and views the dataset's), in
// Material::pair_gains's layout. Per present pair: the model image is the subspace's CPU synthesis
// (seed `seed`) times its tone share times the relit factor of the pair's light, as the render pass
// composes it seen from above; its gains are found by fixed-point steps on linear RGB until its Lab
// mean is the measured image's, both over the same grid of about kPairGainSamples pixels. A missing
// pair, or one whose model or measurement is black, keeps gain 1. `threads` 0: all hardware threads;
// `progress` is called once per light, from any thread.
inline constexpr std::size_t kPairGainSamples = 16384;  // a Lab mean's sampling error about 0.1 delta E
std::vector<std::uint8_t> fit_pair_gains(const BtfDataset& dataset, const Material& material,
                                         const PairGainRelief& relief, std::uint64_t seed,
                                         unsigned threads = 0, const std::function<void()>& progress = {});

}  // namespace carbtf
