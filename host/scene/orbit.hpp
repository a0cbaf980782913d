// Scene set-up in the commands' terms: directions given as elevation and azimuth in degrees (the
// convention of the BTF directions: theta from +z, phi from +x towards +y), and cameras on an orbit
// around the origin.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "carbtf/engine/render/mesh_renderer.hpp"

namespace carbtf::cli {

// The unit vector towards (theta, phi), in degrees.
std::array<float, 3> unit_vector_degrees(double theta_degrees, double phi_degrees);

// A camera at `distance` from the origin towards (theta, phi), looking at the origin, z up (y up when
// it looks straight down the z axis); perspective with `fov_y_degrees`, or orthographic for 0.
RenderCamera orbit_camera(double theta_degrees, double phi_degrees, float distance,
                          float fov_y_degrees = 40.0f);

// The scene of `carbtf render`'s options: an orbit camera (theta, phi in degrees[, distance, default
// 3.6]), directional lights (theta, phi[, intensity]) and point lights (x, y, z[, intensity]); one
// light at (45, 120) when none is given. CommandError for a distance not above 0 or too many lights.
RenderScene scene_from_options(const std::vector<double>& camera, float fov_y_degrees,
                               const std::vector<std::vector<double>>& lights,
                               const std::vector<std::vector<double>>& point_lights);

// Frame i of n of `bench frame`: the camera orbits at 60 degrees from the pole, 3.6 away, and
// `lights` directional lights (1 to kMaxRenderLights; CommandError otherwise) the other way at 40
// degrees, spread evenly in azimuth, each 1 / lights strong.
RenderScene orbiting_scene(std::uint32_t i, std::uint32_t n, std::uint32_t lights = 1);

// The demo's sphere seen from 60 degrees off the pole at azimuth 35 + `turn` degrees, 3.4 away, under
// a key light and a dim bluish fill that turn with it (0: the front; 180: the back, where u wraps).
RenderScene demo_sphere_scene(float turn_degrees);

}  // namespace carbtf::cli
