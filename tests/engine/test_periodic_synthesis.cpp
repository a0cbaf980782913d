// Periodic subspace images for closed meshes (docs/design.md 4.4, "Periodic output"): the GPU fold
// equals the CPU reference bit for bit, it leaves the rest of the block as the plain synthesis, and the
// texture across the wrap has the statistics it has inside (a plain block fails the same check).
#include <catch2/catch.hpp>

#include <cmath>

#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "gpu_reference_harness.hpp"
#include "test_range_tiles.hpp"
#include "test_support.hpp"

using namespace carbtf;

namespace {

// Mean squared difference of channel values `lag` texels apart along rows (horizontal) or columns, over
// the pairs inside the image, and over the pairs that straddle the wrap (the last `lag` texels of a row
// or column with the first ones).
struct WrapDifferences {
  double inside = 0.0;
  double across = 0.0;
};
WrapDifferences wrap_differences(const std::vector<float>& image, std::uint32_t width, std::uint32_t height,
                                 std::uint32_t channels, std::uint32_t lag, bool horizontal) {
  auto at = [&](std::uint32_t x, std::uint32_t y, std::uint32_t c) {
    return double{image[(std::size_t{y} * width + x) * channels + c]};
  };
  const std::uint32_t along = horizontal ? width : height, across_lines = horizontal ? height : width;
  double inside = 0.0, across = 0.0;
  std::size_t inside_count = 0, across_count = 0;
  for (std::uint32_t line = 0; line < across_lines; ++line) {
    for (std::uint32_t i = 0; i < along; ++i) {
      const std::uint32_t j = (i + lag) % along;
      for (std::uint32_t c = 0; c < channels; ++c) {
        const double a = horizontal ? at(i, line, c) : at(line, i, c);
        const double b = horizontal ? at(j, line, c) : at(line, j, c);
        (j > i ? inside : across) += (a - b) * (a - b);
        ++(j > i ? inside_count : across_count);
      }
    }
  }
  return {inside / inside_count, across / across_count};
}

// The variance of the first `columns` columns (where the fold blends) and of the rest.
std::pair<double, double> fold_and_rest_variance(const std::vector<float>& image, std::uint32_t width,
                                                 std::uint32_t height, std::uint32_t channels,
                                                 std::uint32_t columns) {
  double sum[2] = {0, 0}, square[2] = {0, 0};
  std::size_t count[2] = {0, 0};
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      const int part = x < columns ? 0 : 1;
      const double v = image[(std::size_t{y} * width + x) * channels];
      sum[part] += v;
      square[part] += v * v;
      ++count[part];
    }
  }
  auto variance = [&](int p) { return square[p] / count[p] - (sum[p] / count[p]) * (sum[p] / count[p]); };
  return {variance(0), variance(1)};
}

}  // namespace

TEST_CASE("periodic GPU subspace images equal the CPU reference bit for bit across schemes and batches",
          "[gpu_synthesis][gpu][periodic]") {
  test::ValidatedContext context;
  auto synthesizer = test::make_synthesizer(*context);
  const Material m = synthetic_material(3, 3);
  SynthesisRequest request;
  request.seed = 91;
  request.row0 = -7;
  request.col0 = 13;
  request.width = 75;
  request.height = 33;
  request.margin = 20;
  request.periodic_overlap = 9;
  request.subspaces = {2, 0};
  request.poison = true;
  // One batch, then one band stack per batch: the colour sums of a folded image continue across batches.
  test::SynthesisMatrix matrix;
  matrix.batch_caps = {0, 64 * 1024};
  for (const test::MatrixRun& run : test::require_gpu_matches_reference(*synthesizer, m, request, matrix)) {
    CHECK(run.images.width == 75);
    CHECK(run.images.height == 33);
  }
  request.periodic_overlap = 34;  // more than the 33 rows
  SynthesizedImages images;
  const Status status = synthesizer->synthesize(m, request, images);
  CHECK(status.code() == ErrorCode::invalid_argument);
  CHECK_THAT(status.message(), Catch::Contains("periodic overlap 34"));
  context.require_clean();
}

TEST_CASE("a periodic image keeps the plain synthesis of the larger block beyond its fold", "[periodic]") {
  const Material m = synthetic_material(2, 3);
  SynthesisBlock periodic;
  periodic.seed = 5;
  periodic.width = 64;
  periodic.height = 48;
  periodic.margin = 24;
  periodic.periodic_overlap = 8;
  SynthesisBlock plain = periodic;
  plain.periodic_overlap = 0;
  plain.width += 8;
  plain.height += 8;
  const std::vector<float> folded = test::reference_subspace(m, 1, periodic),
                           whole = test::reference_subspace(m, 1, plain);
  const std::uint32_t channels = m.subspaces[1].channels;
  std::size_t same = 0, folded_differs = 0;
  for (std::uint32_t y = 0; y < periodic.height; ++y) {
    for (std::uint32_t x = 0; x < periodic.width; ++x) {
      for (std::uint32_t c = 0; c < channels; ++c) {
        const float a = folded[(std::size_t{y} * periodic.width + x) * channels + c];
        const float b = whole[(std::size_t{y} * plain.width + x) * channels + c];
        if (x >= 8 && y >= 8) {
          same += a == b;
        } else {
          folded_differs += a != b;
        }
      }
    }
  }
  CHECK(same == std::size_t{56} * 40 * channels);
  // The fold changes the texels it blends (all of them but none by chance alone).
  CHECK(folded_differs > (std::size_t{64} * 48 - std::size_t{56} * 40) * channels * 9 / 10);
}

TEST_CASE("across the wrap a periodic image has the statistics it has inside and a plain one does not",
          "[periodic]") {
  const Material m = synthetic_material(3, 3);
  SynthesisBlock block;
  block.seed = 2024;
  block.width = 256;
  block.height = 256;
  block.margin = 64;
  block.periodic_overlap = default_periodic_overlap(256, 256);
  REQUIRE(block.periodic_overlap == 32);
  SynthesisBlock plain = block;
  plain.periodic_overlap = 0;
  for (std::uint32_t s = 0; s < 3; ++s) {
    const std::uint32_t channels = m.subspaces[s].channels;
    const std::vector<float> periodic_image = test::reference_subspace(m, s, block),
                             plain_image = test::reference_subspace(m, s, plain);
    for (bool horizontal : {true, false}) {
      for (std::uint32_t lag : {1u, 2u}) {
        INFO("subspace " << s << (horizontal ? ", along rows" : ", along columns") << ", lag " << lag);
        const WrapDifferences periodic =
            wrap_differences(periodic_image, 256, 256, channels, lag, horizontal);
        const WrapDifferences cut = wrap_differences(plain_image, 256, 256, channels, lag, horizontal);
        INFO("periodic: inside " << periodic.inside << ", across " << periodic.across << "; plain: inside "
                                 << cut.inside << ", across " << cut.across);
        // 256 lines x lag pairs straddle the wrap: a sampling error of about 10% at lag 1.
        CHECK(periodic.across / periodic.inside > 0.7);
        CHECK(periodic.across / periodic.inside < 1.4);
        CHECK(cut.across / cut.inside > 1.5);
      }
    }
    // The fold keeps the variance where it blends (weights whose squares sum to 1).
    const auto [fold, rest] = fold_and_rest_variance(periodic_image, 256, 256, channels, 32);
    INFO("subspace " << s << ": variance in the fold " << fold << ", beyond it " << rest);
    CHECK(fold / rest > 0.85);
    CHECK(fold / rest < 1.15);
  }
}

TEST_CASE("a periodic range map repeats its tile grid or folds and has no seam at the wrap", "[periodic]") {
  const RangeTiles tiles = test::windowed_range_tiles(
      [](std::uint32_t r, std::uint32_t c) { return 3 * std::sin(r / 9.0) + 2 * std::cos(c / 11.0); }, {});
  REQUIRE(tiles.tile_size == 16);
  for (const std::uint32_t width : {64u, 60u}) {
    INFO("width " << width << (width % 16 == 0 ? ": whole tiles, the grid repeats" : ": folded"));
    TextureWindow block{3, -5, 9, width, 48, 8};
    std::vector<float> periodic(std::size_t{width} * 48), plain(periodic.size());
    enlarge_range_map(tiles, block, periodic);
    block.periodic_overlap = 0;
    enlarge_range_map(tiles, block, plain);
    for (bool horizontal : {true, false}) {
      const WrapDifferences wrapped = wrap_differences(periodic, width, 48, 1, 1, horizontal);
      const WrapDifferences cut = wrap_differences(plain, width, 48, 1, 1, horizontal);
      INFO((horizontal ? "along rows" : "along columns")
           << ": periodic inside " << wrapped.inside << ", across " << wrapped.across << "; plain inside "
           << cut.inside << ", across " << cut.across);
      CHECK(wrapped.across < 1.5 * wrapped.inside);
      CHECK(cut.across > 2.0 * cut.inside);
    }
    if (width % 16 == 0) {
      // The same block one period further right and down is the same map.
      std::vector<float> shifted(periodic.size());
      enlarge_range_map(tiles, TextureWindow{3, -5 + 48, 9 + 64, width, 48, 8}, shifted);
      CHECK(shifted == periodic);
    }
  }
}

TEST_CASE("closed shapes and meshes whose texture coordinates wrap ask for periodic textures", "[periodic]") {
  CHECK(make_sphere().periodic_uv);
  CHECK(make_cylinder().periodic_uv);
  CHECK(make_torus().periodic_uv);
  CHECK_FALSE(make_plane().periodic_uv);
  // As a file would give them: the detection finds the shapes' seams, and coordinates beyond [0, 1].
  CHECK(texture_coordinates_wrap(make_sphere()));
  CHECK(texture_coordinates_wrap(make_torus()));
  CHECK_FALSE(texture_coordinates_wrap(make_plane(4)));
  Mesh repeated = make_plane(4);
  for (MeshVertex& v : repeated.vertices) v.uv[0] *= 3.0f;
  CHECK(texture_coordinates_wrap(repeated));
}
