// Integrating a normal map into a range (height) map, by robust least squares on the texel grid.
//
// The heights h are fitted so that the render pass's normals, the central differences of h, are the
// given normals: (h[x + 1] - h[x - 1]) / 2 = g[x] for the gradient g = (-nx / nz, ny / nz), with a
// weaker forward difference per texel that ties neighbouring texels, on a periodic grid (as Frankot &
// Chellappa's Fourier-domain projection treated it). The fit is robust: photometric stereo's normals
// are wrong in creases (shadowed, lit by their walls), and wrong normals are not integrable. A plain
// least-squares fit (Frankot-Chellappa is one) spreads their error over the cells around them: leather's
// flat cells came out tilted and hatched under grazing light, the render's normals 8.4 degrees off the
// truth there. Iteratively reweighted least squares, with Cauchy weights on each equation's residual,
// keeps it in the crease (2.4 degrees; docs/design.md 5.3). The mean height is removed. Heights are
// in texel units. The model stores this map as it is (analyze.cpp's relief_of()).
#pragma once

#include <span>

#include "carbtf/analysis/model/plane.hpp"

namespace carbtf {

// How many times the weights are refitted to the residuals (each a preconditioned conjugate-gradient
// solve, surface_integration.cpp).
inline constexpr int kRobustIntegrationRounds = 3;

// `normals` is width * height * 3 (x right, y up, z out); nz is clamped to at least 0.1 so grazing
// estimates cannot produce unbounded slopes. Throws std::invalid_argument for an empty or short map.
Plane integrate_normals(std::span<const float> normals, std::uint32_t width, std::uint32_t height);

}  // namespace carbtf
