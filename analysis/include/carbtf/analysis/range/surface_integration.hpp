// Integrating a normal map into a range (height) map, Frankot & Chellappa (1988): the gradient field
// implied by the normals is projected onto the nearest integrable one in the Fourier domain. The
// derivative is taken as i 2 sin(w / 2), which follows the true derivative at low frequencies and never
// vanishes below Nyquist, so per-pixel noise in estimated normals is not amplified into
// high-frequency ripple (the central difference, i sin w, vanishes at Nyquist). The map is treated as
// periodic; the mean height is removed. Heights are in texel units.
#pragma once

#include <span>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// `normals` is width * height * 3 (x right, y up, z out); nz is clamped to at least 0.1 so grazing
// estimates cannot produce unbounded slopes.
Plane integrate_normals(std::span<const float> normals, std::uint32_t width, std::uint32_t height);

}  // namespace carbtf
