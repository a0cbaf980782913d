// The light and view direction sets of one material, built once (docs/design.md 4.5): both
// triangulations (direction_interpolation.hpp), their lookup grids for the fragment stage, the 9 pair
// weights of any (light, view) query, and the subspace images a set of (light, view) pairs needs. The
// binding, the scene pruner, the CPU references and the commands all take their directions from here.
// Thread safety: a built object is immutable; its queries are pure.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/status.hpp"

namespace carbtf {

// A lookup grid of one direction set, for the fragment stage (carbtf_material.glsl): the projected disk
// [-1, 1]^2 cut into grid_size^2 cells, each listing the triangles that meet it and the
// boundary edges that can be nearest to a point of it.
struct DirectionLookupGrid {
  std::uint32_t grid_size = 0;
  std::vector<std::uint32_t> cell_starts;  // grid_size^2 + 1; cell (x, y) is index y * grid_size + x
  std::vector<std::uint32_t> entries;      // triangle index, or CARBTF_LOOKUP_EDGE_BIT | edge index
};

class MaterialDirections {
 public:
  // `grid_size` in [1, 256]: the lookup grids' cells per side (MaterialBindingInfo::lookup_grid_size).
  // Fails (invalid_argument) when a direction set cannot be triangulated or the grid size is out of range.
  static Status build(const Material& material, MaterialDirections& out,
                      std::uint32_t grid_size = 64) noexcept;

  const DirectionTriangulation& light_triangulation() const noexcept { return lights_; }
  const DirectionTriangulation& view_triangulation() const noexcept { return views_; }
  const DirectionLookupGrid& light_grid() const noexcept { return light_grid_; }
  const DirectionLookupGrid& view_grid() const noexcept { return view_grid_; }

  // The pair weights of a (light, view) query in radians (pair_weights()).
  PairWeights weights(double light_theta, double light_phi, double view_theta, double view_phi,
                      PairCoupling coupling = PairCoupling::product) const;

  // The subspace images that carry non-zero weight, in the order the weights first name them.
  std::vector<std::uint32_t> subspaces_of(const PairWeights& weights) const;
  // The subspace images of measured (light, view) index pairs, sorted, each once.
  std::vector<std::uint32_t> subspaces_of(
      std::span<const std::pair<std::uint32_t, std::uint32_t>> pairs) const;

 private:
  DirectionTriangulation lights_, views_;
  DirectionLookupGrid light_grid_, view_grid_;
  std::vector<std::uint8_t> subspace_index_;  // the material's, [light * view_count_ + view]
  std::uint32_t view_count_ = 0;
};

}  // namespace carbtf
