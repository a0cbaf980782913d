// The relief's chroma one mip level above its brightness (carbtf_material_shade() and its CPU twin,
// render_reference.cpp): creases and facets finer than two texels change the colour's brightness, not its
// chroma, as in a measured image whose colour the camera and JPEG's 4:2:0 band-limit. The GPU's picture
// is the reference's to a documented tolerance (test_render.cpp), so the reference stands for both here.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "carbtf/reference/render_reference.hpp"
#include "test_materials.hpp"

namespace carbtf {
namespace {

constexpr std::uint32_t kSize = 64;

// Encoded luma (Rec. 601 over x^(1/2.4)) and colour differences of a linear colour.
struct Encoded {
  double luma;
  double difference[3];
};

Encoded encoded(const float* rgb) {
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = std::pow(std::max(0.0, double{rgb[k]}), 1.0 / 2.4);
  Encoded out{0.299 * e[0] + 0.587 * e[1] + 0.114 * e[2], {}};
  for (int k = 0; k < 3; ++k) out.difference[k] = e[k] - out.luma;
  return out;
}

}  // namespace

TEST_CASE("the relief's fine facets change the colour's brightness and not its chroma", "[render]") {
  // Ridges across x with a period of 4 texels, heights 0, 0, 1, 1: their normals tilt -, +, +, - along x,
  // so at level 0 the facets face towards and away from a light from +x in turn, and the means of two
  // neighbours, level 1, are flat everywhere.
  std::vector<float> heights(kSize * kSize);
  for (std::uint32_t r = 0; r < kSize; ++r)
    for (std::uint32_t c = 0; c < kSize; ++c) heights[r * kSize + c] = (c % 4) >= 2 ? 1.0f : 0.0f;
  const Material material = test::bumpy_material();  // its directions and subspaces; no tone
  SynthesizedImages images;
  images.width = images.height = kSize;
  for (std::size_t s = 0; s < material.subspaces.size(); ++s) {
    images.channels.push_back(3);
    std::vector<float> image(3 * kSize * kSize);
    for (std::size_t i = 0; i < image.size(); i += 3) {
      image[i] = 0.6f;  // a saturated brown, the same everywhere
      image[i + 1] = 0.3f;
      image[i + 2] = 0.1f;
    }
    images.images.push_back(std::move(image));
  }
  reference::ReferenceRenderInput input;
  input.material = &material;
  input.images = &images;
  input.range_map = heights;
  input.parallax_scale = 0.0f;
  input.wrap = true;
  input.mip_levels = 1;  // the picture at level 0, its chroma from level 1
  RenderScene scene;
  scene.camera.eye = {0.0f, 0.0f, 3.0f};
  scene.camera.up = {0.0f, 1.0f, 0.0f};
  scene.camera.fov_y_degrees = 0.0f;
  scene.camera.ortho_height = 2.0f;  // one texel per pixel
  const float light_theta = 0.25f * 3.14159265f;
  scene.lights = {{false, {std::sin(light_theta), 0.0f, std::cos(light_theta)}, {1.0f, 1.0f, 1.0f}}};
  const std::vector<float> picture = reference::render_plane(input, scene, kSize, kSize, {0, 0, 0, 0});

  double luma_low = 1e9, luma_high = -1e9, difference_spread = 0.0;
  const Encoded first = encoded(&picture[4 * (8 * kSize + 8)]);
  for (std::uint32_t r = 8; r < kSize - 8; ++r) {
    for (std::uint32_t c = 8; c < kSize - 8; ++c) {
      const float* pixel = &picture[4 * (r * kSize + c)];
      REQUIRE(pixel[3] == 1.0f);
      const Encoded e = encoded(pixel);
      luma_low = std::min(luma_low, e.luma);
      luma_high = std::max(luma_high, e.luma);
      for (int k = 0; k < 3; ++k)
        difference_spread = std::max(difference_spread, std::abs(e.difference[k] - first.difference[k]));
    }
  }
  INFO("encoded luma " << luma_low << " to " << luma_high << ", colour differences within "
                       << difference_spread);
  // The facets light and darken the brown by a third of its encoded value and more...
  CHECK(luma_high - luma_low > 0.2);
  // ... while its colour differences stay those of the flat level above: with the chroma at the facets'
  // own level they swing by 0.09 (measured with the chroma read at level 0), 40% of the luma's range.
  CHECK(difference_spread < 0.005 * (luma_high - luma_low));
}

}  // namespace carbtf
