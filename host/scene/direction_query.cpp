#include "scene/direction_query.hpp"

#include <algorithm>
#include <numbers>
#include <string>

#include "cli/cli_support.hpp"

namespace carbtf::cli {

Interpolation interpolation_of(const Material& material, const std::vector<double>& light,
                               const std::vector<double>& view) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  MaterialDirections directions;
  check(MaterialDirections::build(material, directions), "cannot interpolate the material's directions");
  Interpolation interpolation;
  interpolation.weights =
      directions.weights(light[0] * kDegree, light[1] * kDegree, view[0] * kDegree, view[1] * kDegree);
  interpolation.subspaces = directions.subspaces_of(interpolation.weights);
  return interpolation;
}

std::vector<std::uint32_t> subspaces_with(const std::vector<std::uint32_t>& requested,
                                          const Interpolation& interpolation) {
  if (requested.empty()) return interpolation.subspaces;
  for (std::uint32_t s : interpolation.subspaces) {
    if (std::find(requested.begin(), requested.end(), s) == requested.end()) {
      throw CommandError("the (light, view) image needs subspace " + std::to_string(s) +
                         ", which --subspaces leaves out");
    }
  }
  return requested;
}

}  // namespace carbtf::cli
