// Scene set-up in the commands' terms: directions given as elevation and azimuth in degrees (the
// convention of the BTF directions: theta from +z, phi from +x towards +y), and cameras on an orbit
// around the origin.
#pragma once

#include <array>

#include "carbtf/engine/mesh_renderer.hpp"

namespace carbtf::cli {

// The unit vector towards (theta, phi), in degrees.
std::array<float, 3> unit_vector_degrees(double theta_degrees, double phi_degrees);

// A camera at `distance` from the origin towards (theta, phi), looking at the origin, z up (y up when
// it looks straight down the z axis); perspective with `fov_y_degrees`, or orthographic for 0.
RenderCamera orbit_camera(double theta_degrees, double phi_degrees, float distance,
                          float fov_y_degrees = 40.0f);

}  // namespace carbtf::cli
