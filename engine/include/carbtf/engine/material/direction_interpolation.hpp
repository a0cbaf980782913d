// Barycentric interpolation over measured directions (paper Sec. III "BTF Interpolation", docs/design.md 4.5).
//
// The measured directions of one set (lights or views) are mapped to the unit disk by the azimuthal
// equidistant projection, (x, y) = theta / (pi / 2) * (cos phi, sin phi), which keeps the elevation
// rings evenly spaced and is continuous across phi = 0, and triangulated there (Delaunay, Bowyer-Watson).
// A query direction gets the barycentric weights of the triangle holding its projection; beyond the
// outermost measured ring (outside the triangulation) it takes the nearest point of the boundary, so
// its weights fall on the two ends of a boundary edge. Weights are continuous in the direction, sum
// to 1, and are exactly (1, 0, 0) at a measured direction. A (light, view) query multiplies the light
// and view weights into 9 weights of 9 (light, view) pairs.
// Thread safety: a built triangulation is immutable; queries are pure.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

struct DirectionTriangulation {
  std::vector<std::array<double, 2>> points;           // projected directions, one per measured direction
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise
  std::vector<std::array<std::uint32_t, 2>> boundary;   // edges of the outer boundary
};

// Needs at least 3 directions not all on one line in the projection (else invalid_argument); a single
// direction or two are allowed and give a degenerate triangulation (all weight on the nearest).
Status build_direction_triangulation(std::span<const MaterialDirection> directions, DirectionTriangulation& out);

// The projection of (theta, phi) into the unit disk.
std::array<double, 2> project_direction(double theta, double phi);

struct DirectionWeights {
  std::array<std::uint32_t, 3> index{};  // measured directions
  std::array<float, 3> weight{};         // sum to 1; unused entries have weight 0
};
DirectionWeights direction_weights(const DirectionTriangulation& triangulation, double theta, double phi);

struct PairWeights {
  std::array<std::uint32_t, 9> light{};
  std::array<std::uint32_t, 9> view{};
  std::array<float, 9> weight{};
};
PairWeights pair_weights(const DirectionTriangulation& lights, const DirectionTriangulation& views, double light_theta,
                         double light_phi, double view_theta, double view_phi);

}  // namespace carbtf
