#include "carbtf/engine/render/rendered_values.hpp"

#include <algorithm>
#include <cmath>

#include <carbtf_gpu_shared.h>
#include <glm/gtc/packing.hpp>

namespace carbtf {

float rendered_tone_weight(float tone_weight) noexcept {
  return glm::unpackHalf1x16(glm::packHalf1x16(tone_weight));
}

std::uint32_t pair_gain_units(float gain) noexcept {
  return static_cast<std::uint32_t>(std::clamp(std::lround(gain * gpu::CARBTF_PAIR_GAIN_UNITS), 0l, 1023l));
}

std::array<float, 3> rendered_pair_gain(const Material& material, std::uint32_t light,
                                        std::uint32_t view) noexcept {
  std::array<float, 3> gain{};
  for (std::uint32_t c = 0; c < 3; ++c)
    gain[c] = static_cast<float>(pair_gain_units(pair_gain(material, light, view, c))) /
              gpu::CARBTF_PAIR_GAIN_UNITS;
  return gain;
}

std::array<float, 3> relief_chroma_mix(const std::array<float, 3>& colour,
                                       const std::array<float, 3>& chroma_colour) noexcept {
  constexpr float kGamma = gpu::CARBTF_CHROMA_GAMMA;
  constexpr std::array<float, 3> kLuma{gpu::CARBTF_LUMA_RED, gpu::CARBTF_LUMA_GREEN, gpu::CARBTF_LUMA_BLUE};
  std::array<float, 3> encoded{}, chroma_encoded{};
  float luma = 0.0f, chroma_luma = 0.0f;
  for (std::size_t k = 0; k < 3; ++k) {
    encoded[k] = std::pow(std::max(colour[k], 0.0f), kGamma);
    chroma_encoded[k] = std::pow(std::max(chroma_colour[k], 0.0f), kGamma);
    luma += kLuma[k] * encoded[k];
    chroma_luma += kLuma[k] * chroma_encoded[k];
  }
  std::array<float, 3> mixed{};
  for (std::size_t k = 0; k < 3; ++k)
    mixed[k] = std::pow(std::max(luma + (chroma_encoded[k] - chroma_luma), 0.0f), 1.0f / kGamma);
  return mixed;
}

}  // namespace carbtf
