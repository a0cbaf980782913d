#include "scene/orbit.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "cli/cli_support.hpp"

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

RenderScene scene_from_options(const std::vector<double>& camera, float fov_y_degrees,
                               const std::vector<std::vector<double>>& lights,
                               const std::vector<std::vector<double>>& point_lights) {
  RenderScene scene;
  const float distance = camera.size() > 2 ? static_cast<float>(camera[2]) : 3.6f;
  if (!(distance > 0.0f)) throw CommandError("--camera: the distance must be above 0");
  scene.camera = orbit_camera(camera[0], camera[1], distance, fov_y_degrees);
  for (const auto& light : lights) {
    const float intensity = light.size() > 2 ? static_cast<float>(light[2]) : 1.0f;
    scene.lights.push_back(
        {false, unit_vector_degrees(light[0], light[1]), {intensity, intensity, intensity}});
  }
  for (const auto& light : point_lights) {
    const float intensity = light.size() > 3 ? static_cast<float>(light[3]) : 1.0f;
    scene.lights.push_back(
        {true,
         {static_cast<float>(light[0]), static_cast<float>(light[1]), static_cast<float>(light[2])},
         {intensity, intensity, intensity}});
  }
  if (scene.lights.empty()) scene.lights.push_back({false, unit_vector_degrees(45.0, 120.0), {1, 1, 1}});
  if (scene.lights.size() > kMaxRenderLights) {
    throw CommandError("at most " + std::to_string(kMaxRenderLights) +
                       " lights (--light and --point-light together)");
  }
  return scene;
}

RenderScene orbiting_scene(std::uint32_t i, std::uint32_t n, std::uint32_t lights) {
  const double turn = 360.0 * i / std::max(n, 1u);
  RenderScene scene;
  scene.camera = orbit_camera(60.0, 35.0 + turn, 3.6f);
  if (lights == 0 || lights > kMaxRenderLights) {
    throw CommandError("--lights: " + std::to_string(lights) + " is not in 1-" +
                       std::to_string(kMaxRenderLights) + " (the lights one draw shades with)");
  }
  const std::uint32_t count = lights;
  const float strength = 1.0f / static_cast<float>(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    scene.lights.push_back(
        {false, unit_vector_degrees(40.0, 120.0 - turn + 360.0 * k / count), {strength, strength, strength}});
  }
  return scene;
}

RenderScene demo_sphere_scene(float turn_degrees) {
  RenderScene scene;
  const std::array<float, 3> eye = unit_vector_degrees(60, 35 + turn_degrees);
  scene.camera.eye = {3.4f * eye[0], 3.4f * eye[1], 3.4f * eye[2]};
  scene.lights = {{false, unit_vector_degrees(50, 80 + turn_degrees), {1, 1, 1}},
                  {false, unit_vector_degrees(70, 250 + turn_degrees), {0.25f, 0.25f, 0.3f}}};
  return scene;
}

}  // namespace carbtf::cli
