// The render pass's parallax ray march (reference/parallax_march.hpp, the CPU twin of
// carbtf_parallax_uv()): the texture point it finds is the first one the view ray meets, as a march in
// steps of a five-hundredth of a texel finds it, ridges hiding what lies behind them.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "carbtf/reference/parallax_march.hpp"

namespace {

constexpr std::uint32_t kSize = 64;

// A periodic relief of ridges and pits, 2.6 texels from its mean at most, slopes up to about 1:
// steep enough that at 60 degrees from the top a ridge hides the foot of the slope behind it.
struct Relief {
  std::vector<float> heights = std::vector<float>(kSize * kSize);
  Relief() {
    const double w = 2.0 * std::numbers::pi / kSize;
    for (std::uint32_t r = 0; r < kSize; ++r)
      for (std::uint32_t c = 0; c < kSize; ++c)
        heights[r * kSize + c] =
            static_cast<float>(1.3 * std::sin(5 * w * c + 0.4) * std::cos(3 * w * r) +
                               0.9 * std::sin(4 * w * (c + r) + 1.1) + 0.4 * std::cos(7 * w * r - 2 * w * c));
  }
  // Bilinear at uv, texel centres at (i + 0.5) / kSize, wrapping, minus the mean (as the render pass reads
  // it).
  float at(glm::vec2 uv, float mean) const {
    const glm::vec2 t = uv * static_cast<float>(kSize) - 0.5f;
    const glm::vec2 base = glm::floor(t), f = t - base;
    auto h = [&](int x, int y) {
      const auto n = static_cast<int>(kSize);
      return heights[static_cast<std::size_t>(((y % n + n) % n) * n + ((x % n + n) % n))];
    };
    const int x = static_cast<int>(base.x), y = static_cast<int>(base.y);
    const float top = h(x, y) + f.x * (h(x + 1, y) - h(x, y));
    const float bottom = h(x, y + 1) + f.x * (h(x + 1, y + 1) - h(x, y + 1));
    return top + f.y * (bottom - top) - mean;
  }
};

glm::vec3 direction(double theta_degrees, double phi_degrees) {
  const double t = theta_degrees * std::numbers::pi / 180, p = phi_degrees * std::numbers::pi / 180;
  return glm::vec3(static_cast<float>(std::sin(t) * std::cos(p)),
                   static_cast<float>(std::sin(t) * std::sin(p)), static_cast<float>(std::cos(t)));
}

// The first point of the relief on the ray from the eye through plane point uv, marched in steps of
// 1/500 texel of the ray's length from above the highest point (in double).
glm::dvec2 first_hit(const Relief& relief, float mean, const carbtf::ReliefExtent& extent, glm::vec2 uv,
                     glm::vec3 view) {
  const glm::dvec2 uv_per_t = glm::dvec2(view.x, -view.y) / static_cast<double>(kSize);
  const double top = extent.top / view.z, bottom = extent.bottom / view.z;
  for (double t = top + 0.01; t > bottom - 0.01; t -= 0.002) {
    const glm::dvec2 at = glm::dvec2(uv) + t * uv_per_t;
    if (t * view.z <= relief.at(glm::vec2(at), mean)) return at;
  }
  return glm::dvec2(uv) + static_cast<double>(extent.bottom / view.z) * uv_per_t;
}

struct Agreement {
  double within = 0.0;      // share of plane points whose hit is within 0.05 texels of the first hit
  double mean_error = 0.0;  // texels
};

Agreement agreement(const Relief& relief, glm::vec3 view, std::uint32_t steps) {
  const carbtf::ReliefExtent extent = carbtf::relief_extent(relief.heights, 1.0f);
  const auto height_at = [&](glm::vec2 uv) { return relief.at(uv, extent.mean); };
  const glm::vec2 size(static_cast<float>(kSize));
  Agreement a;
  std::uint32_t points = 0;
  for (std::uint32_t r = 0; r < kSize; r += 2) {
    for (std::uint32_t c = 0; c < kSize; c += 2) {
      const glm::vec2 uv((static_cast<float>(c) + 0.25f) / kSize, (static_cast<float>(r) + 0.75f) / kSize);
      const glm::vec2 marched =
          carbtf::reference::parallax_march(height_at, uv, view, size, 1.0f, extent, steps);
      const double error =
          glm::length(glm::dvec2(marched) - first_hit(relief, extent.mean, extent, uv, view)) * kSize;
      a.within += error <= 0.05 ? 1.0 : 0.0;
      a.mean_error += error;
      ++points;
    }
  }
  a.within /= points;
  a.mean_error /= points;
  return a;
}

}  // namespace

TEST_CASE("the parallax march finds the first point of the relief the view ray meets", "[parallax]") {
  const Relief relief;
  for (const auto& [theta, phi] : {std::pair{30.0, 20.0}, {45.0, 200.0}, {60.0, 54.0}, {75.0, 300.0}}) {
    const glm::vec3 view = direction(theta, phi);
    const Agreement march = agreement(relief, view, carbtf::kDefaultParallaxSteps);
    const Agreement offset_mapping = agreement(relief, view, 0);
    INFO("view (" << theta << ", " << phi << "): the march within 0.05 texels at " << march.within
                  << " of the points, mean error " << march.mean_error << " texels; offset mapping at "
                  << offset_mapping.within << ", mean error " << offset_mapping.mean_error);
    // Where the march's half-texel steps pass over a ridge's tip that the fine march grazes, it lands on
    // the slope behind: a few points at most.
    CHECK(march.within >= 0.97);
    CHECK(march.mean_error <= 0.05);
    // Offset mapping reads the height at the plane point, not where the ray meets the relief.
    CHECK(offset_mapping.mean_error >= 5 * march.mean_error);
  }
}

TEST_CASE("the parallax march leaves uv where the view is straight down or the relief flat", "[parallax]") {
  const Relief relief;
  const carbtf::ReliefExtent extent = carbtf::relief_extent(relief.heights, 1.0f);
  const auto height_at = [&](glm::vec2 uv) { return relief.at(uv, extent.mean); };
  const glm::vec2 uv(0.3f, 0.6f), size(static_cast<float>(kSize));
  CHECK(carbtf::reference::parallax_march(height_at, uv, glm::vec3(0, 0, 1), size, 1.0f, extent, 32) == uv);
  const std::vector<float> flat(kSize * kSize, 2.0f);
  const carbtf::ReliefExtent none = carbtf::relief_extent(flat, 1.0f);
  CHECK(none.top == 0.0f);
  CHECK(none.bottom == 0.0f);
  CHECK(carbtf::reference::parallax_march([](glm::vec2) { return 0.0f; }, uv, direction(60, 10), size, 1.0f,
                                          none, 32) == uv);
  // A negative scale turns the relief over: its top is the lowest height's.
  const carbtf::ReliefExtent turned = carbtf::relief_extent(relief.heights, -1.0f);
  CHECK(turned.top == -extent.bottom);
  CHECK(turned.bottom == -extent.top);
}
