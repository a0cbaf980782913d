// Offline renderer of a height field as a UBO2003-style BTF: for every (light, view) pair an
// orthographic image rectified to the sample plane, with masking (the visible point is found by ray
// marching the height field along the view direction) and cast shadows (marching towards the light),
// shaded Lambertian plus a normalised Blinn-Phong lobe. Deterministic: no random sampling.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/sample/surface.hpp"

namespace carbtf {

struct RenderOptions {
  unsigned threads = 0;     // 0: all hardware threads
  bool progress = true;     // progress bar on stderr when it is a terminal
  float irradiance = 2.5f;  // light irradiance at normal incidence (pi would map white Lambert to 1)
  float ambient = 0.03f;    // unshadowed ambient term, times albedo
};

// Per texel, 1 where the surface point sees `light` and 0 where the height field casts a shadow on it
// (size * size, row-major): the renderer's own shadow test, for judging estimates on unshadowed texels.
std::vector<float> light_visibility(const Surface& surface, const Direction& light);

// Calls `emit(light, view, image)` once per pair, image = size * size * 3 linear RGB, from worker
// threads (emit must be thread-safe). Throws std::invalid_argument for an empty surface.
void render_btf(const Surface& surface, const std::vector<Direction>& lights,
                const std::vector<Direction>& views, const RenderOptions& options,
                const std::function<void(std::uint32_t, std::uint32_t, std::span<const float>)>& emit);

}  // namespace carbtf
