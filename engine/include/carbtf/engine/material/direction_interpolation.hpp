// Barycentric interpolation over measured directions (paper Sec. III "BTF Interpolation",
// docs/design.md 4.5).
//
// The measured directions of one set (lights or views) are mapped to the unit disk by the azimuthal
// equidistant projection, (x, y) = theta / (pi / 2) * (cos phi, sin phi), which keeps the elevation
// rings evenly spaced and is continuous across phi = 0, and triangulated there (Delaunay, Bowyer-Watson).
// A query direction gets the barycentric weights of the triangle holding its projection; beyond the
// outermost measured ring (outside the triangulation) it takes the nearest point of the boundary, so
// its weights fall on the two ends of a boundary edge. Weights are continuous in the direction, sum
// to 1, and are exactly (1, 0, 0) at a measured direction. A (light, view) query combines the light
// and view weights into weights of (light, view) pairs (PairCoupling below).
// Thread safety: a built triangulation is immutable; queries are pure.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/material/material.hpp"

namespace carbtf {

struct DirectionTriangulation {
  std::vector<std::array<double, 2>> points;            // projected directions, one per measured direction
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise
  std::vector<std::array<std::uint32_t, 2>> boundary;   // edges of the outer boundary
};

// Needs at least 3 directions not all on one line in the projection (else invalid_argument); a single
// direction or two are allowed and give a degenerate triangulation (all weight on the nearest).
Status build_direction_triangulation(std::span<const MaterialDirection> directions,
                                     DirectionTriangulation& out);

// The projection of (theta, phi) into the unit disk.
std::array<double, 2> project_direction(double theta, double phi);

struct DirectionWeights {
  std::array<std::uint32_t, 3> index{};  // measured directions
  std::array<float, 3> weight{};         // sum to 1; unused entries have weight 0
};
DirectionWeights direction_weights(const DirectionTriangulation& triangulation, double theta, double phi);

// Weights of (light, view) pairs; pairs that take no part have weight 0.
struct PairWeights {
  std::array<std::uint32_t, 9> light{};
  std::array<std::uint32_t, 9> view{};
  std::array<float, 9> weight{};
};

// How a light's 3 weights and a view's 3 weights combine into pair weights. Both are exact at measured
// pairs (weight 1 on the pair), continuous in the directions, and keep the light's and the view's
// weights as their sums over views and over lights; they differ by what the 3 x 3 pairs hold beyond a
// light part plus a view part.
enum class PairCoupling : std::uint8_t {
  // The paper's 9 weights: every light weight times every view weight.
  product,
  // At most 5 pairs (carbtf_gpu_shared.h, carbtf_staircase_next_is_light()): the render pass reads 5
  // subspace images per light instead of 9. Linear between the measured pairs where the product is
  // bilinear, as tetrahedral interpolation of a colour table is where trilinear is: the light's and the
  // view's weights, each ordered by direction index, laid end to end on [0, 1], and each pair given the
  // length its two intervals share (the comonotone coupling). The order by index makes two triangles
  // that share an edge order its two directions alike, so the weights stay continuous across it.
  staircase,
};

// Slots 0-8 of the product (light-major); slots 0-4 of the staircase, the rest weight 0.
PairWeights couple_pair_weights(const DirectionWeights& light, const DirectionWeights& view,
                                PairCoupling coupling);
PairWeights pair_weights(const DirectionTriangulation& lights, const DirectionTriangulation& views,
                         double light_theta, double light_phi, double view_theta, double view_phi,
                         PairCoupling coupling = PairCoupling::product);

}  // namespace carbtf
