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

}  // namespace carbtf
