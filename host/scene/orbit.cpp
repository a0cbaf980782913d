#include "scene/orbit.hpp"

#include <cmath>
#include <numbers>

namespace carbtf::cli {

std::array<float, 3> unit_vector_degrees(double theta_degrees, double phi_degrees) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  const double t = theta_degrees * kDegree, p = phi_degrees * kDegree;
  return {static_cast<float>(std::sin(t) * std::cos(p)), static_cast<float>(std::sin(t) * std::sin(p)),
          static_cast<float>(std::cos(t))};
}

RenderCamera orbit_camera(double theta_degrees, double phi_degrees, float distance, float fov_y_degrees) {
  const auto towards = unit_vector_degrees(theta_degrees, phi_degrees);
  RenderCamera camera;
  camera.eye = {distance * towards[0], distance * towards[1], distance * towards[2]};
  camera.up = std::abs(towards[2]) > 0.999f ? std::array<float, 3>{0, 1, 0} : std::array<float, 3>{0, 0, 1};
  camera.fov_y_degrees = fov_y_degrees;
  camera.ortho_height = 2.4f;
  camera.far_plane = distance + 10.0f;
  return camera;
}

}  // namespace carbtf::cli
