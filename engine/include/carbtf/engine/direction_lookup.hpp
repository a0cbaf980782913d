// Lookup grids for the fragment stage's direction interpolation (carbtf_material.glsl): a fragment
// finds the measured triangle around its projected direction without searching the triangulation.
// The projected disk [-1, 1]^2 is cut into grid_size^2 cells; each cell lists the triangles whose
// bounding box meets it and, where part of the cell lies outside the triangulation, the boundary
// edges that can be nearest to a point of the cell. The shader tests only its own cell's list.
// Thread safety: built grids are immutable; queries are pure.
#pragma once

#include <cstdint>
#include <vector>

#include "carbtf/engine/direction_interpolation.hpp"

namespace carbtf {

struct DirectionLookupGrid {
  std::uint32_t grid_size = 0;
  std::vector<std::uint32_t> cell_starts;  // grid_size^2 + 1; cell (x, y) is index y * grid_size + x
  std::vector<std::uint32_t> entries;      // triangle index, or CARBTF_LOOKUP_EDGE_BIT | edge index
};

// grid_size in [1, 256].
DirectionLookupGrid build_direction_lookup(const DirectionTriangulation& triangulation, std::uint32_t grid_size = 32);

// The weights the fragment stage computes from a grid for projected point (x, y), with the shader's
// float arithmetic; within float rounding of direction_weights() for the same direction.
DirectionWeights lookup_direction_weights(const DirectionLookupGrid& grid, const DirectionTriangulation& triangulation,
                                          float x, float y);

}  // namespace carbtf
