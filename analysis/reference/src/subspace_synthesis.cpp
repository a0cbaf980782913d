#include "carbtf/reference/subspace_synthesis.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <carbtf_periodic.h>
#include <carbtf_steps.h>

#include "carbtf/engine/internal/synthesis_layout.hpp"
#include "carbtf/reference/car_synthesis.hpp"
#include "carbtf/reference/parallel_for.hpp"

namespace carbtf::reference {
namespace {

template <typename Real>
constexpr Real kExpandWeight[5] = {Real(2) * Real(1) / Real(16), Real(2) * Real(4) / Real(16),
                                   Real(2) * Real(6) / Real(16), Real(2) * Real(4) / Real(16),
                                   Real(2) * Real(1) / Real(16)};

// Expands `coarse` (over region `from`) to region `to`, rows first, then columns.
template <typename Real>
std::vector<Real> expand(const std::vector<Real>& coarse, const TextureRegion& from,
                         const TextureRegion& to) {
  // Along rows: every coarse row, fine columns.
  std::vector<Real> horizontal(static_cast<std::size_t>(from.rows * to.cols));
  for (std::int64_t r = 0; r < from.rows; ++r) {
    for (std::int64_t c = 0; c < to.cols; ++c) {
      const std::int64_t i = to.col0 + c;
      Real acc{0};
      for (int k = -2; k <= 2; ++k) {
        if (((i - k) & 1) != 0) continue;
        const std::int64_t j = (i - k) / 2 - from.col0;  // i - k even: exact division
        acc = gpu::carbtf_weighted_add(acc, kExpandWeight<Real>[k + 2],
                                       coarse[static_cast<std::size_t>(r * from.cols + j)]);
      }
      horizontal[static_cast<std::size_t>(r * to.cols + c)] = acc;
    }
  }
  std::vector<Real> out(static_cast<std::size_t>(to.rows * to.cols));
  for (std::int64_t r = 0; r < to.rows; ++r) {
    const std::int64_t i = to.row0 + r;
    for (std::int64_t c = 0; c < to.cols; ++c) {
      Real acc{0};
      for (int k = -2; k <= 2; ++k) {
        if (((i - k) & 1) != 0) continue;
        const std::int64_t j = (i - k) / 2 - from.row0;
        acc = gpu::carbtf_weighted_add(acc, kExpandWeight<Real>[k + 2],
                                       horizontal[static_cast<std::size_t>(j * to.cols + c)]);
      }
      out[static_cast<std::size_t>(r * to.cols + c)] = acc;
    }
  }
  return out;
}

// Adds `coarser` (the collapsed level above, over `from`), expanded to `to`, to `band`: one collapse step.
template <typename Real>
void add_expanded(std::vector<Real>& band, const std::vector<Real>& coarser, const TextureRegion& from,
                  const TextureRegion& to) {
  const std::vector<Real> expanded = expand(coarser, from, to);
  for (std::size_t i = 0; i < band.size(); ++i) band[i] = band[i] + expanded[i];
}

void check_subspace(const Material& material, std::uint32_t subspace) {
  if (subspace >= material.subspaces.size())
    throw std::invalid_argument("subspace " + std::to_string(subspace) + " does not exist");
}

template <typename Real>
void synthesize(const Material& material, std::uint32_t subspace, const SubspaceBlock& block,
                std::span<Real> out, SubspaceStages* stages, std::span<const float> initial_values) {
  check_subspace(material, subspace);
  const SubspaceModel& model = material.subspaces[subspace];
  const std::uint32_t single[1] = {subspace};
  const BlockFrameLayout frames =
      initial_values.empty() ? BlockFrameLayout{} : block_frame_layout(material, block, single);
  if (!initial_values.empty() && initial_values.size() != frames.floats) {
    throw std::invalid_argument(
        "subspace " + std::to_string(subspace) + ": " + std::to_string(initial_values.size()) +
        " block initialization values, the block needs " + std::to_string(frames.floats));
  }
  if (block.periodic_overlap > std::min(block.width, block.height))
    throw std::invalid_argument("subspace synthesis: the periodic overlap exceeds the image's shorter side");
  const std::size_t pixels = std::size_t{block.width} * block.height;
  if (out.size() < pixels * model.channels)
    throw std::invalid_argument("subspace synthesis: output span too small");
  if (!within_texture_coordinates(block))
    throw std::invalid_argument("subspace synthesis: the block lies beyond the 32-bit texture coordinates");
  const std::vector<TextureRegion> regions = level_regions(synthesized_region(block), model.levels);

  if (stages) {
    stages->regions = regions;
    stages->band.assign(std::size_t{model.levels} * model.channels, {});
  }
  for (std::uint32_t channel = 0; channel < model.channels; ++channel) {
    std::vector<Real> current;
    for (std::uint32_t level = model.levels; level-- > 0;) {
      const TextureRegion& region = regions[level];
      CarFieldBlock field;
      field.seed = block.seed;
      field.field_id = field_id_of(subspace, level, channel);
      field.row0 = region.row0;
      field.col0 = region.col0;
      field.width = static_cast<std::uint32_t>(region.cols);
      field.height = static_cast<std::uint32_t>(region.rows);
      field.margin = band_burn_in(model.bands[std::size_t{level} * model.channels + channel], block.margin);
      if (!initial_values.empty()) {
        const BlockFrameField& frame = frames.fields[std::size_t{level} * model.channels + channel];
        field.frame = initial_values.subspan(frame.offset, car_frame_floats(frame.car, frame.pad));
      }
      std::vector<Real> band(static_cast<std::size_t>(region.rows * region.cols));
      synthesize_car_block(model.bands[level * model.channels + channel], field, std::span<Real>(band));
      const std::size_t index = std::size_t{level} * model.channels + channel;
      if constexpr (std::is_same_v<Real, float>) {
        if (stages) stages->band[index] = band;
      }
      if (level + 1 < model.levels) add_expanded(band, current, regions[level + 1], region);
      current = std::move(band);
    }
    // The collapsed channel, folded when periodic (carbtf_periodic.h), waits in `out` for the colour
    // step: no second image-sized buffer.
    gpu::carbtf_fold_grid<Real>(current, block.width, block.height, block.periodic_overlap,
                                static_cast<Real>(collapsed_band_mean(model, channel)), out.data() + channel,
                                model.channels);
  }
  std::vector<Real> collapsed(model.channels);
  for (std::size_t p = 0; p < pixels; ++p) {
    std::copy_n(out.begin() + static_cast<std::ptrdiff_t>(p * model.channels), model.channels,
                collapsed.begin());
    for (std::uint32_t i = 0; i < model.channels; ++i) {
      Real acc = static_cast<Real>(model.colour_mean[i]);
      for (std::uint32_t j = 0; j < model.channels; ++j) {
        acc = gpu::carbtf_weighted_add(
            acc, static_cast<Real>(model.colour_transform[std::size_t{i} * model.channels + j]),
            collapsed[j]);
      }
      out[p * model.channels + i] = acc;
    }
  }
}

std::vector<std::uint32_t> resolve_list(const Material& material, std::span<const std::uint32_t> subspaces) {
  std::vector<std::uint32_t> list(subspaces.begin(), subspaces.end());
  if (list.empty()) {
    for (std::uint32_t s = 0; s < material.subspaces.size(); ++s) list.push_back(s);
  }
  for (std::uint32_t s : list) check_subspace(material, s);
  return list;
}

template <typename Real>
std::vector<std::vector<Real>> synthesize_many(const Material& material,
                                               std::span<const std::uint32_t> subspaces,
                                               const SubspaceBlock& block, unsigned threads,
                                               std::span<const float> initial_values) {
  const std::vector<std::uint32_t> list = resolve_list(material, subspaces);
  // Each subspace's frames are consecutive in the layout: slice them per task.
  std::vector<std::span<const float>> slices(list.size());
  if (!initial_values.empty()) {
    const BlockFrameLayout layout = block_frame_layout(material, block, list);
    if (initial_values.size() != layout.floats) {
      throw std::invalid_argument(std::to_string(initial_values.size()) +
                                  " block initialization values, the block needs " +
                                  std::to_string(layout.floats));
    }
    std::size_t field = 0;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const SubspaceModel& model = material.subspaces[list[i]];
      const std::size_t count = std::size_t{model.levels} * model.channels;
      const std::uint64_t begin = layout.fields[field].offset;
      const std::uint64_t end =
          field + count < layout.fields.size() ? layout.fields[field + count].offset : layout.floats;
      slices[i] = initial_values.subspan(begin, end - begin);
      field += count;
    }
  }
  std::vector<std::vector<Real>> images(material.subspaces.size());
  for (std::uint32_t s : list)
    images[s].resize(std::size_t{block.width} * block.height * material.subspaces[s].channels);
  detail::parallel_for(list.size(), threads, [&](std::size_t i) {
    synthesize(material, list[i], block, std::span<Real>(images[list[i]]), nullptr, slices[i]);
  });
  return images;
}

}  // namespace

std::vector<std::vector<float>> synthesize_subspaces(const Material& material,
                                                     std::span<const std::uint32_t> subspaces,
                                                     const SubspaceBlock& block, unsigned threads,
                                                     std::span<const float> initial_values) {
  return synthesize_many<float>(material, subspaces, block, threads, initial_values);
}

std::vector<std::vector<double>> synthesize_subspaces_f64(const Material& material,
                                                          std::span<const std::uint32_t> subspaces,
                                                          const SubspaceBlock& block, unsigned threads,
                                                          std::span<const float> initial_values) {
  return synthesize_many<double>(material, subspaces, block, threads, initial_values);
}

void synthesize_subspace(const Material& material, std::uint32_t subspace, const SubspaceBlock& block,
                         std::span<float> out, SubspaceStages* stages,
                         std::span<const float> initial_values) {
  synthesize(material, subspace, block, out, stages, initial_values);
}
void synthesize_subspace(const Material& material, std::uint32_t subspace, const SubspaceBlock& block,
                         std::span<double> out, std::span<const float> initial_values) {
  synthesize(material, subspace, block, out, nullptr, initial_values);
}

void collapse_band_stages(SubspaceStages& stages) {
  const std::size_t levels = stages.regions.size();
  if (levels == 0 || stages.band.size() % levels != 0)
    throw std::invalid_argument("collapse_band_stages: stages do not match their regions");
  const std::size_t channels = stages.band.size() / levels;
  for (std::size_t channel = 0; channel < channels; ++channel) {
    for (std::size_t level = levels - 1; level-- > 0;) {
      add_expanded(stages.band[level * channels + channel], stages.band[(level + 1) * channels + channel],
                   stages.regions[level + 1], stages.regions[level]);
    }
  }
}

std::vector<std::vector<float>> block_initial_values(const Material& material,
                                                     std::span<const std::uint32_t> subspaces,
                                                     const SubspaceBlock& whole,
                                                     std::span<const SubspaceBlock> blocks,
                                                     unsigned threads) {
  const std::vector<std::uint32_t> list = resolve_list(material, subspaces);
  std::vector<BlockFrameLayout> layouts;
  std::vector<std::vector<float>> values;
  for (const SubspaceBlock& block : blocks) {
    if (block.seed != whole.seed)
      throw std::invalid_argument(
          "block initialization values: a block's seed differs from the whole synthesis's");
    layouts.push_back(block_frame_layout(material, block, list));
    values.emplace_back(layouts.back().floats);
  }
  // One task per (subspace, level, channel) band of the whole; layouts share the field order.
  const std::vector<BlockFrameField> bands = block_frame_layout(material, whole, list).fields;
  detail::parallel_for(bands.size(), threads, [&](std::size_t i) {
    const BlockFrameField& band = bands[i];
    const SubspaceModel& model = material.subspaces[band.subspace];
    const TextureRegion level = level_regions(synthesized_region(whole), model.levels)[band.level];
    CarFieldBlock field;
    field.seed = whole.seed;
    field.field_id = field_id_of(band.subspace, band.level, band.channel);
    field.row0 = level.row0;
    field.col0 = level.col0;
    field.width = static_cast<std::uint32_t>(level.cols);
    field.height = static_cast<std::uint32_t>(level.rows);
    const CarBandModel& band_model = model.bands[std::size_t{band.level} * model.channels + band.channel];
    field.margin = band_burn_in(band_model, whole.margin);
    const CarFieldValues source = synthesize_car_field(band_model, field);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const BlockFrameField& target = layouts[b].fields[i];
      const std::size_t count = car_frame_floats(target.car, target.pad);
      if (!extract_car_frame(target.car, target.pad, source.values, source.region,
                             std::span<float>(values[b]).subspan(target.offset, count))) {
        throw std::invalid_argument(
            "block " + std::to_string(b) + " (" + std::to_string(blocks[b].width) + "x" +
            std::to_string(blocks[b].height) + " at row " + std::to_string(blocks[b].row0) + ", col " +
            std::to_string(blocks[b].col0) + ", margin " + std::to_string(blocks[b].margin) +
            ") does not lie inside the whole synthesis with its burn-in margin and frame");
      }
    }
  });
  return values;
}

void interpolate_subspaces(const Material& material, const PairWeights& weights,
                           const std::vector<std::vector<float>>& images, std::span<float> out) {
  std::fill(out.begin(), out.end(), 0.0f);
  for (int k = 0; k < 9; ++k) {
    if (weights.weight[k] == 0.0f) continue;
    const std::uint32_t s = subspace_of(material, weights.light[k], weights.view[k]);
    if (s >= images.size() || images[s].size() < out.size()) {
      throw std::invalid_argument("interpolation needs subspace image " + std::to_string(s) +
                                  ", which was not synthesized");
    }
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = gpu::carbtf_weighted_add(out[i], weights.weight[k], images[s][i]);
  }
}

}  // namespace carbtf::reference
