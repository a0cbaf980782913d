#include "synthesis/synthesis_plan.hpp"

#include <algorithm>
#include <limits>
#include <string>

#include "vulkan/vk_check.hpp"

namespace carbtf::detail {
namespace {

// The fields of one (subspace, channel): all its levels, laid out later.
struct Stack {
  std::uint32_t subspace = 0;
  std::uint32_t channel = 0;
  std::vector<PlannedField> levels;
  std::uint64_t floats = 0;
};

std::uint64_t padded_floats(const gpu::CarFieldGpu& field) {
  return std::uint64_t{field.rows + field.pad} * field.pitch;
}

// The frame of field (subspace, level, channel) in the request's initial values, or none.
std::uint32_t frame_offset_of(const BlockFrameLayout* frames, std::uint32_t subspace, std::uint32_t level,
                              std::uint32_t channel) {
  if (frames == nullptr) return gpu::CARBTF_NO_FRAME;
  for (const BlockFrameField& field : frames->fields) {
    if (field.subspace == subspace && field.level == level && field.channel == channel) {
      return static_cast<std::uint32_t>(field.offset);
    }
  }
  return gpu::CARBTF_NO_FRAME;
}

Status make_stack(const Material& material, std::uint32_t subspace, std::uint32_t channel,
                  const std::vector<TextureRegion>& regions, std::uint32_t margin,
                  const BlockFrameLayout* frames, Stack& out) {
  const SubspaceModel& model = material.subspaces[subspace];
  out.subspace = subspace;
  out.channel = channel;
  for (std::uint32_t level = 0; level < model.levels; ++level) {
    const CarBandModel& band = model.bands[std::size_t{level} * model.channels + channel];
    if (band.neighbourhood.size() > kMaxGpuNeighbours) {
      return {ErrorCode::invalid_argument,
              "subspace " + std::to_string(subspace) + " level " + std::to_string(level) + " channel " +
                  std::to_string(channel) + " has " + std::to_string(band.neighbourhood.size()) +
                  " CAR neighbours; the GPU synthesis supports at most " + std::to_string(kMaxGpuNeighbours) +
                  " (the CPU reference, `carbtf synth --device cpu`, has no such limit)"};
    }
    PlannedField field;
    field.subspace = subspace;
    field.level = level;
    field.channel = channel;
    field.window = regions[level];
    gpu::CarFieldGpu& g = field.gpu;
    const TextureRegion car = car_region(field.window, band_burn_in(band, margin));
    g.pad = car_frame_pad(band.neighbourhood);
    g.rows = static_cast<std::uint32_t>(car.rows);
    g.cols = static_cast<std::uint32_t>(car.cols);
    g.pitch = g.cols + 2 * g.pad;
    g.field_id = field_id_of(subspace, level, channel);
    g.row0 = static_cast<std::uint32_t>(static_cast<std::int32_t>(car.row0));
    g.col0 = static_cast<std::uint32_t>(static_cast<std::int32_t>(car.col0));
    g.neighbour_count = static_cast<std::uint32_t>(band.neighbourhood.size());
    g.skew = car_wavefront_skew(band.neighbourhood);
    g.frame_offset = frame_offset_of(frames, subspace, level, channel);
    g.sigma = band.sigma;
    for (std::size_t k = 0; k < band.neighbourhood.size(); ++k) {
      g.tap[k] = int{band.neighbourhood[k].dr} * static_cast<int>(g.pitch) + int{band.neighbourhood[k].dc};
      g.gamma[k] = band.gamma[k];
    }
    out.floats += padded_floats(g);
    out.levels.push_back(field);
  }
  return {};
}

void finish_batch(const Material& material, std::vector<Stack>& stacks, const SynthesisPlan& plan,
                  PlannedBatch& batch) {
  // Level-major order: lockstep groups of the serial kernel then hold fields of one size.
  std::uint32_t max_levels = 0;
  for (const Stack& stack : stacks)
    max_levels = std::max<std::uint32_t>(max_levels, static_cast<std::uint32_t>(stack.levels.size()));
  std::vector<std::vector<std::size_t>> field_index(stacks.size());
  for (std::uint32_t level = 0; level < max_levels; ++level) {
    LevelGroup group;
    group.first = static_cast<std::uint32_t>(batch.fields.size());
    std::vector<std::size_t> order;
    for (std::size_t s = 0; s < stacks.size(); ++s) {
      if (level < stacks[s].levels.size()) order.push_back(s);
    }
    const auto variant_of = [&](std::size_t s) {
      return car_tap_variant(stacks[s].levels[level].gpu.neighbour_count);
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return variant_of(a) < variant_of(b); });
    for (const std::size_t s : order) {
      PlannedField field = stacks[s].levels[level];
      field.gpu.offset = static_cast<std::uint32_t>(batch.window_floats);
      batch.window_floats += padded_floats(field.gpu);
      ++group.count;
      group.max_padded_rows = std::max(group.max_padded_rows, field.gpu.rows + field.gpu.pad);
      group.max_pitch = std::max(group.max_pitch, field.gpu.pitch);
      group.max_window_rows = std::max(group.max_window_rows, static_cast<std::uint32_t>(field.window.rows));
      group.max_window_cols = std::max(group.max_window_cols, static_cast<std::uint32_t>(field.window.cols));
      group.max_frame_cells = std::max(group.max_frame_cells,
                                       field.gpu.pad * field.gpu.pitch + field.gpu.rows * 2 * field.gpu.pad);
      const std::uint32_t variant = variant_of(s);
      if (batch.car_runs.empty() || batch.car_runs.back().tap_variant != variant ||
          batch.car_runs.back().first < group.first) {
        batch.car_runs.push_back({static_cast<std::uint32_t>(batch.fields.size()), 0, variant, 0, 0, 0});
      }
      CarRun& run = batch.car_runs.back();
      ++run.count;
      run.max_region_quads =
          std::max(run.max_region_quads,
                   std::uint64_t{field.gpu.rows} * gpu::carbtf_noise_quads(field.gpu.col0, field.gpu.cols));
      run.max_region_rows = std::max(run.max_region_rows, field.gpu.rows);
      run.max_steps = std::max(run.max_steps, field.steps());
      field_index[s].push_back(batch.fields.size());
      batch.fields.push_back(field);
    }
    batch.levels.push_back(group);
  }
  batch.collapse.assign(max_levels, {});
  for (std::size_t s = 0; s < stacks.size(); ++s) {
    const std::vector<std::size_t>& indices = field_index[s];
    const SubspaceModel& model = material.subspaces[stacks[s].subspace];
    for (std::size_t level = 0; level < indices.size(); ++level) {
      const PlannedField& fine = batch.fields[indices[level]];
      gpu::CollapseItemGpu item{};
      item.fine_offset = fine.window_element();
      item.fine_pitch = fine.gpu.pitch;
      item.rows = static_cast<std::uint32_t>(fine.window.rows);
      item.cols = static_cast<std::uint32_t>(fine.window.cols);
      item.row0 = static_cast<std::uint32_t>(static_cast<std::int32_t>(fine.window.row0));
      item.col0 = static_cast<std::uint32_t>(static_cast<std::int32_t>(fine.window.col0));
      item.coarse_offset = gpu::CARBTF_NO_FRAME;
      if (level + 1 < indices.size()) {
        const PlannedField& coarse = batch.fields[indices[level + 1]];
        item.coarse_offset = coarse.window_element();
        item.coarse_pitch = coarse.gpu.pitch;
        item.coarse_row0 = static_cast<std::uint32_t>(static_cast<std::int32_t>(coarse.window.row0));
        item.coarse_col0 = static_cast<std::uint32_t>(static_cast<std::int32_t>(coarse.window.col0));
      }
      item.mean = model.bands[level * model.channels + stacks[s].channel].mean;
      batch.collapse[level].push_back(item);
    }
  }
  // One colour item per subspace image in the batch, over its channels here (consecutive stacks).
  for (std::size_t s = 0; s < stacks.size();) {
    const std::uint32_t subspace = stacks[s].subspace;
    const SubspaceModel& model = material.subspaces[subspace];
    gpu::ColourItemGpu item{};
    item.layer = static_cast<std::uint32_t>(
        std::find(plan.subspaces.begin(), plan.subspaces.end(), subspace) - plan.subspaces.begin());
    item.channels = model.channels;
    item.channel_begin = stacks[s].channel;
    item.rows = plan.height;
    item.cols = plan.width;
    item.overlap = plan.periodic_overlap;
    item.inv_overlap = plan.periodic_overlap > 0 ? 1.0f / static_cast<float>(plan.periodic_overlap) : 0.0f;
    for (std::uint32_t i = 0; i < model.channels; ++i) {
      item.mean[i] = model.colour_mean[i];
      item.fold_centre[i] = collapsed_band_mean(model, i);
      for (std::uint32_t j = 0; j < model.channels; ++j) {
        item.transform[i * model.channels + j] = model.colour_transform[std::size_t{i} * model.channels + j];
      }
    }
    for (; s < stacks.size() && stacks[s].subspace == subspace; ++s) {
      const PlannedField& level0 = batch.fields[field_index[s][0]];
      item.offset[stacks[s].channel] = level0.window_element();
      item.pitch[stacks[s].channel] = level0.gpu.pitch;
      item.channel_end = stacks[s].channel + 1;
    }
    batch.colour.push_back(item);
  }
}

}  // namespace

std::uint32_t PlannedField::window_element() const noexcept {
  const std::uint32_t margin = static_cast<std::uint32_t>(gpu.rows - window.rows);
  return gpu.offset + (margin + gpu.pad) * gpu.pitch + margin + gpu.pad;
}

std::uint32_t PlannedField::steps() const noexcept {
  return gpu.skew * (gpu.rows - 1) + gpu.cols;
}

Status plan_synthesis(const Material& material, const SynthesisRequest& request,
                      std::uint64_t max_window_bytes, SynthesisPlan& out) {
  out = {};
  if (request.width == 0 || request.height == 0) {
    return {ErrorCode::invalid_argument, "synthesis size must be at least 1x1"};
  }
  if (request.periodic_overlap > std::min(request.width, request.height)) {
    return {ErrorCode::invalid_argument, "periodic overlap " + std::to_string(request.periodic_overlap) +
                                             " exceeds the " + std::to_string(request.width) + "x" +
                                             std::to_string(request.height) + " image's shorter side"};
  }
  // colour_fold.comp runs one workgroup of CARBTF_FOLD_GROUP per fold texels along x, within the 65,535
  // workgroups every device allows.
  if (std::uint64_t{request.periodic_overlap} * (std::uint64_t{request.width} + request.height) >
      std::uint64_t{gpu::CARBTF_FOLD_GROUP} * 65535u) {
    return {ErrorCode::invalid_argument, "periodic overlap " + std::to_string(request.periodic_overlap) +
                                             " is too wide for a " + std::to_string(request.width) + "x" +
                                             std::to_string(request.height) + " image on the GPU (" +
                                             "default_periodic_overlap() gives at most 64)"};
  }
  if (request.margin > 65536 || !within_texture_coordinates(request)) {
    return {ErrorCode::invalid_argument, "synthesis block or margin beyond the 32-bit texture coordinates"};
  }
  if (request.subspaces.empty()) {
    for (std::uint32_t s = 0; s < material.subspaces.size(); ++s) out.subspaces.push_back(s);
  } else {
    for (std::uint32_t s : request.subspaces) {
      if (s >= material.subspaces.size()) {
        return {ErrorCode::invalid_argument, "subspace " + std::to_string(s) +
                                                 " does not exist (the material has " +
                                                 std::to_string(material.subspaces.size()) + ")"};
      }
      if (std::find(out.subspaces.begin(), out.subspaces.end(), s) != out.subspaces.end()) {
        return {ErrorCode::invalid_argument, "subspace " + std::to_string(s) + " is requested twice"};
      }
      out.subspaces.push_back(s);
    }
  }
  if (out.subspaces.empty()) return {ErrorCode::invalid_argument, "the material has no subspace images"};
  out.width = request.width;
  out.height = request.height;
  out.periodic_overlap = request.periodic_overlap;
  BlockFrameLayout frames;
  if (!request.initial_values.empty()) {
    frames = block_frame_layout(material, request, out.subspaces);
    if (request.initial_values.size() != frames.floats) {
      return {ErrorCode::invalid_argument, "the request has " +
                                               std::to_string(request.initial_values.size()) +
                                               " block initialization values; its block and subspaces need " +
                                               std::to_string(frames.floats)};
    }
    if (frames.floats >= gpu::CARBTF_NO_FRAME) {
      return {ErrorCode::invalid_argument,
              "block initialization values beyond 32-bit offsets; synthesize smaller blocks"};
    }
  }

  std::vector<Stack> all;
  for (std::uint32_t s : out.subspaces) {
    const SubspaceModel& model = material.subspaces[s];
    if (model.channels == 0 || model.channels > kMaxGpuChannels) {
      return {ErrorCode::invalid_argument,
              "subspace " + std::to_string(s) + " has " + std::to_string(model.channels) +
                  " channels; the GPU synthesis supports 1 to " + std::to_string(kMaxGpuChannels) +
                  " (the CPU reference, `carbtf synth --device cpu`, has no such limit)"};
    }
    out.channels.push_back(model.channels);
    const auto regions = level_regions(synthesized_region(request), model.levels);
    for (std::uint32_t c = 0; c < model.channels; ++c) {
      Stack stack;
      CARBTF_TRY(make_stack(material, s, c, regions, request.margin,
                            request.initial_values.empty() ? nullptr : &frames, stack));
      if (stack.floats * sizeof(float) > max_window_bytes) {
        return {ErrorCode::invalid_argument,
                "a " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                    " subspace image with margin " + std::to_string(request.margin) + " needs " +
                    std::to_string(stack.floats * 4 >> 20) + " MiB of work per band, beyond this device's " +
                    std::to_string(max_window_bytes >> 20) +
                    " MiB storage window; synthesize it in smaller blocks"};
      }
      all.push_back(std::move(stack));
    }
  }
  // Greedy batches in (subspace, channel) order, which the colour pass's continuation relies on.
  std::vector<Stack> current;
  std::uint64_t current_floats = 0;
  auto flush = [&]() {
    if (current.empty()) return;
    PlannedBatch batch;
    finish_batch(material, current, out, batch);
    out.window_floats = std::max(out.window_floats, batch.window_floats);
    out.batches.push_back(std::move(batch));
    current.clear();
    current_floats = 0;
  };
  for (Stack& stack : all) {
    if ((current_floats + stack.floats) * sizeof(float) > max_window_bytes) flush();
    current_floats += stack.floats;
    current.push_back(std::move(stack));
  }
  flush();
  return {};
}

}  // namespace carbtf::detail
