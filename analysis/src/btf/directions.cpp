#include "carbtf/analysis/btf/directions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace carbtf {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
}

Direction Direction::from_degrees(double theta_degrees, double phi_degrees) {
  return {theta_degrees * kDegree, phi_degrees * kDegree};
}

Direction Direction::from_vector(const std::array<double, 3>& v) {
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  Direction d;
  d.theta = std::acos(std::clamp(v[2] / length, -1.0, 1.0));
  d.phi = std::atan2(v[1], v[0]);
  if (d.phi < 0) d.phi += 2 * std::numbers::pi;
  return d;
}

std::array<double, 3> Direction::vector() const {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

double Direction::theta_degrees() const {
  return theta / kDegree;
}

double Direction::phi_degrees() const {
  const double degrees = std::fmod(phi / kDegree, 360.0);
  return degrees < 0 ? degrees + 360.0 : degrees;
}

double angle_between(const Direction& a, const Direction& b) {
  const auto u = a.vector(), v = b.vector();
  return std::acos(std::clamp(u[0] * v[0] + u[1] * v[1] + u[2] * v[2], -1.0, 1.0));
}

const std::vector<Direction>& ubo2003_directions() {
  static const std::vector<Direction> directions = [] {
    std::vector<Direction> result;
    const int thetas[] = {0, 15, 30, 45, 60, 75};
    const int counts[] = {1, 6, 12, 18, 20, 24};
    for (int ring = 0; ring < 6; ++ring) {
      for (int k = 0; k < counts[ring]; ++k) {
        result.push_back(Direction::from_degrees(thetas[ring], k * 360.0 / counts[ring]));
      }
    }
    return result;
  }();
  return directions;
}

std::optional<std::uint32_t> ubo2003_index(int theta_degrees, int phi_degrees) {
  const auto& directions = ubo2003_directions();
  for (std::uint32_t i = 0; i < directions.size(); ++i) {
    if (std::lround(directions[i].theta_degrees()) != theta_degrees) continue;
    if (theta_degrees == 0 || std::lround(directions[i].phi_degrees()) == phi_degrees) return i;
  }
  return std::nullopt;
}

}  // namespace carbtf
