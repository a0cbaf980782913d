// Lookup grids for the fragment stage's direction interpolation (carbtf_material.glsl): a fragment
// finds the measured triangle around its projected direction without searching the triangulation.
// The projected disk [-1, 1]^2 is cut into grid_size^2 cells; each cell lists the triangles that
// meet it and, where part of the cell lies outside the triangulation, the boundary
// edges that can be nearest to a point of the cell. The shader tests only its own cell's list.
// Internal to carbtf (not installed): the engine builds the grids for MaterialDirections, and the scene
// pruner and the tests query them.
// Thread safety: built grids are immutable; queries are pure.
#pragma once

#include <cstdint>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material_directions.hpp"

namespace carbtf {

// Whether projected point (x, y) lies in triangle `triangle`, or in any triangle of the triangulation
// (up to 1e-12 barycentric slack).
bool inside_triangle(const DirectionTriangulation& triangulation, std::uint32_t triangle, double x, double y);
bool inside_triangulation(const DirectionTriangulation& triangulation, double x, double y);
// Distance from projected point (x, y) to boundary edge `edge` of the triangulation.
double boundary_edge_distance(const DirectionTriangulation& triangulation, std::uint32_t edge, double x,
                              double y);

// grid_size in [1, 256].
DirectionLookupGrid build_direction_lookup(const DirectionTriangulation& triangulation,
                                           std::uint32_t grid_size = 64);

// The weights the fragment stage computes from a grid for projected point (x, y), with the shader's
// float arithmetic, weights under `min_weight` dropped and the rest renormalised (the shader uses
// CARBTF_LOOKUP_MIN_WEIGHT, 1e-5); within float rounding of direction_weights() for the same direction.
DirectionWeights lookup_direction_weights(const DirectionLookupGrid& grid,
                                          const DirectionTriangulation& triangulation, float x, float y,
                                          float min_weight = 1.0e-5f);

}  // namespace carbtf
