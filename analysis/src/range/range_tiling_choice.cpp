#include "carbtf/analysis/range/range_tiling_choice.hpp"

#include <array>
#include <stdexcept>

#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/model/deshade.hpp"
#include "carbtf/analysis/model/relief_shadows.hpp"
#include "carbtf/analysis/model/relief_tone.hpp"
#include "carbtf/analysis/quality/texture_distributions.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "carbtf/reference/parallel_for.hpp"

namespace carbtf {
namespace {

// The lights the look is rendered under, (elevation, azimuth) in degrees: one from near the top, where
// the tone shows, and four at grazing elevation, where a ridge or a join casts a line of shadow.
constexpr std::array<std::array<double, 2>, 5> kLookLights{
    {{30.0, 0.0}, {75.0, 0.0}, {75.0, 90.0}, {75.0, 180.0}, {75.0, 270.0}}};
// Enlargement layouts scored per candidate: the seeds of the Wang layout (range_tile_at).
constexpr std::array<std::uint64_t, 2> kLookLayouts{1, 2};

// The relief's look under each of kLookLights: tone times the relit heights (apply_relief on white).
std::vector<DistributionStatistics> look_statistics(const Plane& heights, std::span<const Plane> tone,
                                                    const ReliefLook& look) {
  const std::vector<float> horizons =
      look.shadow_scale > 0.0 ? range_map_horizons(heights, look.shadow_scale) : std::vector<float>{};
  std::vector<Plane> tones;  // per colour channel
  for (std::size_t k = 0; k < 3; ++k)
    tones.push_back(tone.empty() ? Plane::Ones(heights.rows(), heights.cols())
                                 : tone[tone.size() == 3 ? k : 0]);
  std::vector<DistributionStatistics> statistics;
  for (const auto& light : kLookLights) {
    const Plane relit = relit_factor(heights, Direction::from_degrees(light[0], light[1]).vector(),
                                     look.light_z_floor, horizons);
    std::vector<float> rgb(static_cast<std::size_t>(heights.size()) * 3, 1.0f);
    apply_relief(rgb, tones, relit);
    statistics.push_back(distribution_statistics(rgb, static_cast<std::uint32_t>(heights.cols()),
                                                 static_cast<std::uint32_t>(heights.rows())));
  }
  return statistics;
}

Plane enlarged_channel(const RangeTiles& tiles, const TextureWindow& window, RangeChannel channel) {
  std::vector<float> values(std::size_t{window.width} * window.height);
  enlarge_range_map(tiles, window, values, channel);
  Plane plane(window.height, window.width);
  for (Eigen::Index i = 0; i < plane.size(); ++i) plane.data()[i] = values[static_cast<std::size_t>(i)];
  return plane;
}

// The mean texture distance of `tiles`' enlargement (the map's size, each of kLookLayouts) from the
// whole map's look `reference` (look_statistics of the map).
double look_distance(const RangeTiles& tiles, std::size_t tone_planes, std::uint32_t width,
                     std::uint32_t height, const ReliefLook& look,
                     const std::vector<DistributionStatistics>& reference) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const std::uint64_t layout : kLookLayouts) {
    const TextureWindow window{layout, 0, 0, width, height, 0};
    const Plane heights = enlarged_channel(tiles, window, RangeChannel::height);
    std::vector<Plane> tone;
    for (std::size_t k = 0; k < tone_planes; ++k)
      tone.push_back(enlarged_channel(tiles, window, tone_channel(k)));
    const std::vector<DistributionStatistics> statistics = look_statistics(heights, tone, look);
    for (std::size_t l = 0; l < statistics.size(); ++l, ++count)
      sum += distribution_distance(statistics[l], reference[l]).total;
  }
  return sum / static_cast<double>(count);
}

}  // namespace

std::uint64_t tiling_candidate_seed(std::uint64_t seed, std::uint32_t index) {
  if (index == 0) return seed;
  // splitmix64 of (seed, index): candidates of neighbouring analysis seeds do not coincide.
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (std::uint64_t{index} + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

RangeTilingChoice choose_range_tiling(const Plane& heights, const RangeTileOptions& options,
                                      std::span<const Plane> tone, const ReliefLook& look,
                                      std::uint32_t candidates, unsigned threads) {
  if (candidates == 0) throw std::invalid_argument("a range tiling choice needs at least one candidate");
  RangeTilingChoice choice;
  std::vector<RangeTiles> built(candidates);
  choice.distances.assign(candidates, 0.0);
  const bool measured = candidates > 1 && heights.rows() >= 16 && heights.cols() >= 16;
  const std::vector<DistributionStatistics> reference =
      measured ? look_statistics(heights, tone, look) : std::vector<DistributionStatistics>{};
  detail::parallel_for(candidates, threads, [&](std::size_t i) {
    RangeTileOptions candidate = options;
    candidate.seed = tiling_candidate_seed(options.seed, static_cast<std::uint32_t>(i));
    built[i] = build_range_tiles(heights, candidate, tone);
    if (measured) {
      choice.distances[i] = look_distance(built[i], tone.size(), static_cast<std::uint32_t>(heights.cols()),
                                          static_cast<std::uint32_t>(heights.rows()), look, reference);
    }
  });
  for (std::size_t i = 1; i < candidates; ++i) {
    if (choice.distances[i] < choice.distances[choice.chosen]) choice.chosen = i;
  }
  choice.seed = tiling_candidate_seed(options.seed, static_cast<std::uint32_t>(choice.chosen));
  choice.tiles = std::move(built[choice.chosen]);
  return choice;
}

}  // namespace carbtf
