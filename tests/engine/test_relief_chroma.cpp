// The relief's chroma RangeTiles::chroma_levels mip levels above its brightness (carbtf_material_shade()
// and its CPU twin, render_reference.cpp): creases and facets finer than the level change the colour's
// brightness, not its chroma, as in a measured image whose colour JPEG's 4:2:0 band-limits; at 0 (a
// measurement with full-resolution colour) they change both. The GPU's picture
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

// Encoded luma range and the widest swing of the encoded colour differences over the inner pixels of a
// plane of ridges across x with a period of 4 texels, heights 0, 0, 1, 1, lit from +x at 45 degrees, the
// relief's chroma read `chroma_levels` levels above its brightness. The ridges' normals tilt -, +, +, -
// along x, so at level 0 the facets face towards and away from the light in turn, and the means of two
// neighbours, level 1, and every level above are flat everywhere.
struct ChromaSwing {
  double luma_range = 0.0;
  double difference_spread = 0.0;
};

ChromaSwing ridge_chroma_swing(std::uint32_t chroma_levels) {
  std::vector<float> heights(kSize * kSize);
  for (std::uint32_t r = 0; r < kSize; ++r)
    for (std::uint32_t c = 0; c < kSize; ++c) heights[r * kSize + c] = (c % 4) >= 2 ? 1.0f : 0.0f;
  Material material = test::bumpy_material();  // its directions and subspaces; no tone
  material.range.chroma_levels = chroma_levels;
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
  input.mip_levels = 1;  // the picture at level 0, its chroma from level chroma_levels
  RenderScene scene;
  scene.camera.eye = {0.0f, 0.0f, 3.0f};
  scene.camera.up = {0.0f, 1.0f, 0.0f};
  scene.camera.fov_y_degrees = 0.0f;
  scene.camera.ortho_height = 2.0f;  // one texel per pixel
  const float light_theta = 0.25f * 3.14159265f;
  scene.lights = {{false, {std::sin(light_theta), 0.0f, std::cos(light_theta)}, {1.0f, 1.0f, 1.0f}}};
  const std::vector<float> picture = reference::render_plane(input, scene, kSize, kSize, {0, 0, 0, 0});

  double luma_low = 1e9, luma_high = -1e9;
  ChromaSwing swing;
  const Encoded first = encoded(&picture[4 * (8 * kSize + 8)]);
  for (std::uint32_t r = 8; r < kSize - 8; ++r) {
    for (std::uint32_t c = 8; c < kSize - 8; ++c) {
      const float* pixel = &picture[4 * (r * kSize + c)];
      REQUIRE(pixel[3] == 1.0f);
      const Encoded e = encoded(pixel);
      luma_low = std::min(luma_low, e.luma);
      luma_high = std::max(luma_high, e.luma);
      for (int k = 0; k < 3; ++k)
        swing.difference_spread =
            std::max(swing.difference_spread, std::abs(e.difference[k] - first.difference[k]));
    }
  }
  swing.luma_range = luma_high - luma_low;
  return swing;
}

}  // namespace

TEST_CASE("the relief's fine facets change the colour's brightness and not its chroma", "[render]") {
  for (const std::uint32_t levels : {1u, 2u}) {
    const ChromaSwing swing = ridge_chroma_swing(levels);
    INFO("chroma " << levels << " levels up: encoded luma range " << swing.luma_range
                   << ", colour differences within " << swing.difference_spread);
    // The facets light and darken the brown by a third of its encoded value and more...
    CHECK(swing.luma_range > 0.2);
    // ... while its colour differences stay those of the flat level above: with the chroma at the facets'
    // own level they swing by 0.09, 40% of the luma's range (below).
    CHECK(swing.difference_spread < 0.005 * swing.luma_range);
  }
}

TEST_CASE("a measurement with full-resolution colour keeps the relief's chroma at the facets' level",
          "[render]") {
  // RangeTiles::chroma_levels 0 (the analysis' choice for PNG or EXR data): the chroma follows the facets.
  const ChromaSwing swing = ridge_chroma_swing(0);
  INFO("encoded luma range " << swing.luma_range << ", colour differences within "
                             << swing.difference_spread);
  CHECK(swing.luma_range > 0.2);
  CHECK(swing.difference_spread > 0.2 * swing.luma_range);
}

}  // namespace carbtf
