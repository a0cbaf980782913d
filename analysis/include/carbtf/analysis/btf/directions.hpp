// Light and view directions over the upper hemisphere of the sample.
//
// Convention (docs/design.md 3): theta is the angle from the surface normal (+z, towards the camera of the
// top view); phi is the azimuth from +x (image right) towards +y (image up, i.e. towards row 0).
// Radians in code, degrees in file names and manifests.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace carbtf {

struct Direction {
  double theta = 0;  // radians, [0, pi/2)
  double phi = 0;    // radians, [0, 2 pi)

  static Direction from_degrees(double theta_degrees, double phi_degrees);
  static Direction from_vector(const std::array<double, 3>& v);  // v need not be unit length
  std::array<double, 3> vector() const;
  double theta_degrees() const;
  double phi_degrees() const;  // in [0, 360)
};

// Angle between two directions, radians.
double angle_between(const Direction& a, const Direction& b);

// The 81 directions of the Bonn UBO2003 BTF database: theta in {0, 15, 30, 45, 60, 75} degrees with
// {1, 6, 12, 18, 20, 24} azimuths phi = k * 360 / count, ordered by theta, then phi.
const std::vector<Direction>& ubo2003_directions();

// Index into ubo2003_directions() of the direction with these integer-degree angles, if any
// (phi is ignored at theta 0, where every azimuth is the same direction).
std::optional<std::uint32_t> ubo2003_index(int theta_degrees, int phi_degrees);

}  // namespace carbtf
