#include "carbtf/analysis/range/range_tile_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "carbtf/engine/material/range_tiles.hpp"

namespace carbtf {
namespace {

// Minimum-error monotone cut for one quadrant: cut[0] = 0, cut[h - 1] = h, cut in [1, h - 1] between.
std::vector<std::uint16_t> best_cut(const RangeTiles& tiles, std::uint32_t tile, TileQuadrant quadrant) {
  const std::uint32_t half = tiles.tile_size / 2;
  const QuadrantPatches patches = quadrant_patches(tiles, tile, quadrant);
  auto error = [&](std::uint32_t u, std::uint32_t v) {
    std::uint32_t x = 0, y = 0;
    quadrant_to_tile(tiles.tile_size, quadrant, u, v, x, y);
    const double d = patch_height_at_tile_texel(tiles, patches.a, x, y) -
                     patch_height_at_tile_texel(tiles, patches.b, x, y);
    return d * d;
  };
  std::vector<std::uint16_t> cut(half, 0);
  cut[half - 1] = static_cast<std::uint16_t>(half);
  if (half < 3) return cut;
  // cost[v][c] for v in [1, h - 2], c in [1, h - 1]; from[v][c] the c of row v - 1 it continues.
  const std::uint32_t rows = half - 2;
  std::vector<double> cost(std::size_t{rows} * half, std::numeric_limits<double>::infinity());
  std::vector<std::uint16_t> from(std::size_t{rows} * half, 0);
  for (std::uint32_t i = 0; i < rows; ++i) {
    const std::uint32_t v = i + 1;
    double best_before = std::numeric_limits<double>::infinity();
    std::uint16_t best_at = 1;
    for (std::uint32_t c = 1; c < half; ++c) {
      if (i > 0 && cost[(i - 1) * half + c] < best_before) {
        best_before = cost[(i - 1) * half + c];
        best_at = static_cast<std::uint16_t>(c);
      }
      const double here = error(c - 1, v) + error(c, v);
      cost[i * half + c] = here + (i == 0 ? 0.0 : best_before);
      from[i * half + c] = best_at;
    }
  }
  std::uint32_t c = 1;
  for (std::uint32_t k = 1; k < half; ++k) {
    if (cost[(rows - 1) * half + k] < cost[(rows - 1) * half + c]) c = k;
  }
  for (std::uint32_t i = rows; i-- > 0;) {
    cut[i + 1] = static_cast<std::uint16_t>(c);
    c = from[i * half + c];
  }
  return cut;
}

// Where a patch is cut from the range map (its top-left texel).
struct PatchOrigin {
  Eigen::Index row = 0, col = 0;
};

// How badly horizontal-edge patch `h` and vertical-edge patch `v` join, over the four quadrants in which
// a tile shows both (see range_tiles.hpp): the squared difference of the two at each texel, relative to
// their variance there, sampled every `stride` texels. Relative, so that flat regions are not preferred
// for being flat; 0 where the two agree texel for texel, about 2 where they are unrelated.
double join_cost(const Plane& map, PatchOrigin h, PatchOrigin v, Eigen::Index half, Eigen::Index stride) {
  // (H window, V window) offsets within the patches, per quadrant: TL, TR, BR, BL.
  constexpr std::array<std::array<int, 4>, 4> kWindows{
      {{1, 0, 0, 1}, {1, 1, 0, 0}, {0, 1, 1, 0}, {0, 0, 1, 1}}};
  double difference = 0.0, spread = 0.0;
  for (const auto& w : kWindows) {
    const Eigen::Index hr = h.row + w[0] * half, hc = h.col + w[1] * half;
    const Eigen::Index vr = v.row + w[2] * half, vc = v.col + w[3] * half;
    double sum_a = 0, sum_b = 0, sum_aa = 0, sum_bb = 0, sum_d = 0, n = 0;
    for (Eigen::Index i = 0; i < half; i += stride) {
      for (Eigen::Index j = 0; j < half; j += stride) {
        const double a = map(hr + i, hc + j), b = map(vr + i, vc + j);
        sum_a += a, sum_b += b, sum_aa += a * a, sum_bb += b * b, sum_d += (a - b) * (a - b), n += 1;
      }
    }
    difference += sum_d;
    spread += (sum_aa - sum_a * sum_a / n) + (sum_bb - sum_b * sum_b / n);
  }
  return spread > 0.0 ? 2.0 * difference / spread : (difference > 0.0 ? 2.0 : 0.0);
}

// The patches' places in the map. Each is drawn at random (seeded), as the Wang-tile method has it. But
// a material that repeats (a weave) shows a cut wherever two patches are out of step with its period, so
// each further patch, alternating between vertical and horizontal, goes instead to the place that joins
// best with the patches of the other orientation already placed (join_cost) where that join is close:
// a mean cost under kCloseJoin, a correlation of about 0.75 or more. Its tiles then show no cut. A
// stochastic material has no such place (its best joins cost 1.5-1.7, measured on the samples) and keeps
// its random patches, and its variety. Places are scored on a grid of samples (every 4th texel, sparser
// for tiles over 256 texels), the best few again on every texel.
constexpr double kCloseJoin = 0.5;
std::vector<PatchOrigin> choose_patch_origins(const Plane& map, std::uint32_t size, std::uint32_t colours,
                                              std::mt19937_64& rng) {
  const auto rows = static_cast<Eigen::Index>(map.rows()) - size + 1;
  const auto cols = static_cast<Eigen::Index>(map.cols()) - size + 1;
  const Eigen::Index half = size / 2;
  std::vector<PatchOrigin> origins(2 * colours);
  for (PatchOrigin& origin : origins) {
    origin.row = static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(rows));
    origin.col = static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(cols));
  }
  std::vector<bool> placed(origins.size(), false);
  placed[0] = true;
  auto cost_of = [&](std::uint32_t patch, PatchOrigin at, Eigen::Index stride) {
    const bool horizontal = patch < colours;
    double cost = 0.0;
    for (std::uint32_t other = horizontal ? colours : 0; other < (horizontal ? 2 * colours : colours);
         ++other) {
      if (placed[other])
        cost += horizontal ? join_cost(map, at, origins[other], half, stride)
                           : join_cost(map, origins[other], at, half, stride);
    }
    return cost;
  };
  constexpr std::size_t kRefined = 16;
  // At most 32 x 32 samples per quadrant in the first scoring: every 4th texel up to 256-texel tiles.
  const Eigen::Index coarse = std::max<Eigen::Index>(4, half / 32);
  // Beyond this many places (a map over about 380^2 with 128-texel tiles), a seeded random sample of
  // them: a period's worth of places holds several in step, so the sample still finds one.
  constexpr Eigen::Index kMostPlaces = 65536;
  for (std::uint32_t k = 1; k < 2 * colours; ++k) {
    const std::uint32_t patch = k % 2 == 1 ? colours + k / 2 : k / 2;  // V0, H1, V1, H2, ...
    std::vector<std::pair<double, PatchOrigin>> scored;
    if (rows * cols <= kMostPlaces) {
      scored.reserve(static_cast<std::size_t>(rows * cols));
      for (Eigen::Index r = 0; r < rows; ++r) {
        for (Eigen::Index c = 0; c < cols; ++c) scored.push_back({cost_of(patch, {r, c}, coarse), {r, c}});
      }
    } else {
      scored.reserve(static_cast<std::size_t>(kMostPlaces));
      for (Eigen::Index i = 0; i < kMostPlaces; ++i) {
        const PatchOrigin at{static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(rows)),
                             static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(cols))};
        scored.push_back({cost_of(patch, at, coarse), at});
      }
    }
    const std::size_t keep = std::min(kRefined, scored.size());
    std::partial_sort(scored.begin(), scored.begin() + static_cast<std::ptrdiff_t>(keep), scored.end(),
                      [](const auto& a, const auto& b) { return a.first < b.first; });
    PatchOrigin best = scored.front().second;
    double best_cost = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < keep; ++i) {
      const double cost = cost_of(patch, scored[i].second, 1);
      if (cost < best_cost) best_cost = cost, best = scored[i].second;
    }
    if (best_cost < kCloseJoin * static_cast<double>((k + 1) / 2)) origins[patch] = best;
    placed[patch] = true;
  }
  return origins;
}

// The stored levels of one texel's tone (`values`, one per plane) quantized at `low + scale * level`,
// levels within [0, top]. One plane: the nearest level. Three (R, G, B): of the 8 ways to round each
// channel down or up, the one whose colour (the channels' log ratios) is nearest the tone's, its
// brightness error counted at a quarter. Rounding each channel to its nearest level on its own draws
// colour speckle where the tone has none: at 4 bits it is visible on fabric's white threads.
std::array<std::uint8_t, 3> tone_levels(const std::array<double, 3>& values, std::size_t planes, double low,
                                        double scale, double top) {
  std::array<std::uint8_t, 3> levels{};
  auto clamped = [&](double level) { return std::clamp(level, 0.0, top); };
  if (!(scale > 0.0)) return levels;
  if (planes != 3) {
    for (std::size_t k = 0; k < planes; ++k)
      levels[k] = static_cast<std::uint8_t>(clamped(std::round((values[k] - low) / scale)));
    return levels;
  }
  constexpr double kFloor = 1e-3;  // tones are at least kReliefToneFloor; this only keeps the logs finite
  constexpr double kBrightnessWeight = 0.25;
  double best = std::numeric_limits<double>::infinity();
  for (unsigned ways = 0; ways < 8; ++ways) {
    std::array<double, 3> level{}, error{};
    for (std::size_t k = 0; k < 3; ++k) {
      const double exact = (values[k] - low) / scale;
      level[k] = clamped((ways >> k & 1u) ? std::ceil(exact) : std::floor(exact));
      error[k] = std::log(std::max(low + scale * level[k], kFloor)) - std::log(std::max(values[k], kFloor));
    }
    const double mean = (error[0] + error[1] + error[2]) / 3.0;
    double cost = 3.0 * kBrightnessWeight * mean * mean;
    for (double e : error) cost += (e - mean) * (e - mean);
    if (cost < best) {
      best = cost;
      for (std::size_t k = 0; k < 3; ++k) levels[k] = static_cast<std::uint8_t>(level[k]);
    }
  }
  return levels;
}

}  // namespace

RangeTiles build_range_tiles(const Plane& heights, const RangeTileOptions& options,
                             std::span<const Plane> tone) {
  if (heights.rows() < 4 || heights.cols() < 4)
    throw std::invalid_argument("a range map needs at least 4 x 4 texels for tiles");
  if (tone.size() != 0 && tone.size() != 1 && tone.size() != 3)
    throw std::invalid_argument("a relief tone has one plane or three");
  for (const Plane& plane : tone) {
    if (plane.rows() != heights.rows() || plane.cols() != heights.cols())
      throw std::invalid_argument("the relief tone is not the range map's size");
  }
  if (options.edge_colours == 0 || options.edge_colours > kMaxEdgeColours)
    throw std::invalid_argument("edge colours must be within 1..4");
  RangeTiles tiles;
  const auto largest = static_cast<std::uint32_t>(std::min(heights.rows(), heights.cols()));
  tiles.tile_size = std::max<std::uint32_t>(4, std::min({options.tile_size, largest, kMaxTileSize}) & ~1u);
  tiles.edge_colours = options.edge_colours;
  tiles.feather = std::min(options.feather, kMaxFeather);
  const double low = heights.minCoeff();
  const double high = heights.maxCoeff();
  tiles.height_offset = static_cast<float>(low);
  if (options.height_bits < 1 || options.height_bits > 16)
    throw std::invalid_argument("height bits must be within 1..16");
  const double top_level = static_cast<double>((1u << options.height_bits) - 1u);
  tiles.height_scale = static_cast<float>((high - low) / top_level);
  const std::uint32_t size = tiles.tile_size;
  std::mt19937_64 rng(options.seed);
  const std::uint32_t patch_count = 2 * tiles.edge_colours;
  tiles.patches.resize(std::size_t{patch_count} * size * size);
  // One quantization over every plane of the tone.
  double tone_low = 0.0, top_tone_level = 0.0;
  if (!tone.empty()) {
    const std::uint32_t tone_bits = tone.size() == 3 ? options.colour_tone_bits : options.tone_bits;
    if (tone_bits < 1 || tone_bits > 8) throw std::invalid_argument("tone bits must be within 1..8");
    top_tone_level = static_cast<double>((1u << tone_bits) - 1u);
    tone_low = tone[0].minCoeff();
    double tone_high = tone[0].maxCoeff();
    for (const Plane& plane : tone) {
      tone_low = std::min(tone_low, plane.minCoeff());
      tone_high = std::max(tone_high, plane.maxCoeff());
    }
    tiles.tone_offset = static_cast<float>(tone_low);
    tiles.tone_scale = static_cast<float>((tone_high - tone_low) / top_tone_level);
    tiles.tone.resize(tiles.patches.size() * tone.size());
  }
  const std::vector<PatchOrigin> origins = choose_patch_origins(heights, size, tiles.edge_colours, rng);
  for (std::uint32_t p = 0; p < patch_count; ++p) {
    const Eigen::Index row0 = origins[p].row, col0 = origins[p].col;
    for (std::uint32_t r = 0; r < size; ++r) {
      for (std::uint32_t c = 0; c < size; ++c) {
        const double h = heights(row0 + r, col0 + c);
        const double q = tiles.height_scale > 0.0f ? std::round((h - low) / tiles.height_scale) : 0.0;
        const std::size_t texel = (std::size_t{p} * size + r) * size + c;
        tiles.patches[texel] = static_cast<std::uint16_t>(std::clamp(q, 0.0, top_level));
        std::array<double, 3> values{};
        for (std::size_t k = 0; k < tone.size(); ++k) values[k] = tone[k](row0 + r, col0 + c);
        const std::array<std::uint8_t, 3> levels =
            tone_levels(values, tone.size(), tone_low, tiles.tone_scale, top_tone_level);
        for (std::size_t k = 0; k < tone.size(); ++k)
          tiles.tone[k * tiles.patches.size() + texel] = levels[k];
      }
    }
  }
  const std::uint32_t half = size / 2;
  tiles.cuts.resize(std::size_t{range_tile_count(tiles)} * 4 * half);
  for (std::uint32_t t = 0; t < range_tile_count(tiles); ++t) {
    for (std::uint32_t q = 0; q < 4; ++q) {
      const auto cut = best_cut(tiles, t, static_cast<TileQuadrant>(q));
      std::copy(cut.begin(), cut.end(),
                tiles.cuts.begin() + static_cast<std::ptrdiff_t>((std::size_t{t} * 4 + q) * half));
    }
  }
  std::vector<PatchWindow> windows;
  for (const PatchOrigin& o : origins)
    windows.push_back({static_cast<std::uint32_t>(o.row), static_cast<std::uint32_t>(o.col)});
  fill_unseen_patch_texels(tiles, windows);
  return tiles;
}

}  // namespace carbtf
