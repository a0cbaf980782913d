#include "carbtf/engine/material/material_directions.hpp"

#include <algorithm>
#include <new>
#include <string>

#include "carbtf/engine/internal/direction_lookup.hpp"

namespace carbtf {

Status MaterialDirections::build(const Material& material, MaterialDirections& out,
                                 std::uint32_t grid_size) noexcept {
  if (grid_size < 1 || grid_size > 256) {
    return {ErrorCode::invalid_argument,
            "direction lookup grid size " + std::to_string(grid_size) + " is outside 1..256"};
  }
  if (material.subspace_index.size() != material.lights.size() * material.views.size()) {
    return {ErrorCode::invalid_argument, "the subspace index has " +
                                             std::to_string(material.subspace_index.size()) +
                                             " entries for " + std::to_string(material.lights.size()) +
                                             " x " + std::to_string(material.views.size()) + " directions"};
  }
  try {
    MaterialDirections built;
    if (Status s = build_direction_triangulation(material.lights, built.lights_); !s.ok()) {
      return {s.code(), "light directions: " + s.message()};
    }
    if (Status s = build_direction_triangulation(material.views, built.views_); !s.ok()) {
      return {s.code(), "view directions: " + s.message()};
    }
    built.light_grid_ = build_direction_lookup(built.lights_, grid_size);
    built.view_grid_ = build_direction_lookup(built.views_, grid_size);
    built.subspace_index_ = material.subspace_index;
    built.view_count_ = static_cast<std::uint32_t>(material.views.size());
    out = std::move(built);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of memory building the direction lookup"};
  }
}

PairWeights MaterialDirections::weights(double light_theta, double light_phi, double view_theta,
                                        double view_phi, PairCoupling coupling) const {
  return pair_weights(lights_, views_, light_theta, light_phi, view_theta, view_phi, coupling);
}

std::vector<std::uint32_t> MaterialDirections::subspaces_of(const PairWeights& weights) const {
  std::vector<std::uint32_t> subspaces;
  for (std::size_t k = 0; k < weights.weight.size(); ++k) {
    if (weights.weight[k] == 0.0f) continue;
    const std::uint32_t s = subspace_index_[std::size_t{weights.light[k]} * view_count_ + weights.view[k]];
    if (std::find(subspaces.begin(), subspaces.end(), s) == subspaces.end()) subspaces.push_back(s);
  }
  return subspaces;
}

std::vector<std::uint32_t> MaterialDirections::subspaces_of(
    std::span<const std::pair<std::uint32_t, std::uint32_t>> pairs) const {
  std::vector<std::uint32_t> subspaces;
  for (const auto& [light, view] : pairs)
    subspaces.push_back(subspace_index_[std::size_t{light} * view_count_ + view]);
  std::sort(subspaces.begin(), subspaces.end());
  subspaces.erase(std::unique(subspaces.begin(), subspaces.end()), subspaces.end());
  return subspaces;
}

}  // namespace carbtf
