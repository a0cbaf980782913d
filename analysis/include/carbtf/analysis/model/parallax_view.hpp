// Where the render pass's parallax ray march (carbtf_parallax_uv, reference/parallax_march.hpp) reads
// the material's textures for each pixel of one view: facets turned towards the view cover more pixels,
// those hidden behind a ridge none, as in the render and in the photograph. A measured image at an
// oblique view holds that parallax, so a model image in texture space is compared with it only after
// it is shown through the same view (the pair gains' Lab means, the subspace models' choice).
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

class ParallaxView {
 public:
  // The march over `range_map` (heights in texel units, as the render pass takes them at the analysis'
  // parallax scale) for the unit direction `view` towards the camera, tangent frame, at the centres of
  // `pixels` (row-major indices into the map's size; empty: every pixel, in order).
  ParallaxView(const Plane& range_map, const std::array<double, 3>& view,
               std::span<const std::size_t> pixels = {});

  // How many pixels the view shows.
  std::size_t size() const { return taps_.size(); }
  // Channel k of shown pixel i of `texture` (row-major, the map's size, `channels` values per texel
  // interleaved), read bilinearly with edges clamped, as the render's sampler reads it.
  float sample(const float* texture, std::size_t channels, std::size_t i, std::size_t k) const;
  // Every shown pixel of `texture`, `channels` values each, interleaved.
  std::vector<float> shown(std::span<const float> texture, std::size_t channels) const;

 private:
  struct Tap {
    std::size_t texel;        // top-left of the bilinear footprint
    std::size_t right, down;  // offsets of the next column and row, 0 at the clamped edge
    float fx, fy;
  };
  static float read(const float* texture, std::size_t channels, const Tap& tap, std::size_t k);
  std::vector<Tap> taps_;
};

}  // namespace carbtf
