#include "carbtf/engine/render/material_binding.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <string>

#include <carbtf_gpu_shared.h>
#include <glm/gtc/packing.hpp>

#include "carbtf/engine/internal/direction_lookup.hpp"
#include "carbtf/engine/material/material_directions.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "carbtf/engine/render/material_tables.hpp"
#include "carbtf/engine/render/relief_horizons.hpp"
#include "carbtf/engine/render/relief_normals.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/vulkan/mip_chain.hpp"
#include "carbtf/engine/vulkan/texture_array.hpp"
#include "vulkan/descriptor_writes.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

namespace {

static_assert(cost_probe::lookups == gpu::CARBTF_COST_PROBE_LOOKUPS &&
                  cost_probe::pair_reads == gpu::CARBTF_COST_PROBE_PAIR_READS &&
                  cost_probe::subspace_reads == gpu::CARBTF_COST_PROBE_SUBSPACE_READS &&
                  cost_probe::relief == gpu::CARBTF_COST_PROBE_RELIEF &&
                  cost_probe::parallax == gpu::CARBTF_COST_PROBE_PARALLAX,
              "the engine's cost probe bits are the shader's");

std::span<const std::uint8_t> as_bytes(const std::vector<float>& values) {
  return {reinterpret_cast<const std::uint8_t*>(values.data()), values.size() * sizeof(float)};
}

// Stages RGBA32F level 0 of one layer of the range texture and its mip levels (next_mip_level(), as
// blits would make them). A normal layer's w is then each texel's own length, so that the fragment
// stage's one filtered read blends the normals' lengths too (carbtf_relief()): 1 at level 0, the length
// of the mean of the unit normals above.
Status set_range_layer(TextureArray& image, std::uint32_t layer, std::vector<float> level, bool normals) {
  std::uint32_t width = image.width(), height = image.height();
  if (normals) store_normal_lengths(level);
  CARBTF_TRY(image.set_layer(layer, as_bytes(level)));
  for (std::uint32_t l = 1; l < image.mip_levels(); ++l) {
    level = next_mip_level(level, width, height, 4);
    width /= 2;
    height /= 2;
    if (normals) store_normal_lengths(level);
    CARBTF_TRY(image.set_level(layer, l, as_bytes(level)));
  }
  return {};
}

}  // namespace

struct MaterialBinding::Resources {
  std::vector<std::uint32_t> tables;
  std::size_t pair_table = 0;  // word offset of the pair table in `tables`, two words per pair
  bool pair_layers = false;    // drawn by (light, view) pair (MaterialTextures::pair_layers)
  std::vector<float> range_map;
  std::vector<float> tone_map;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  Buffer table_buffer;
  UniqueHandle<VkBufferView> table_quads;  // the tables as RGBA32UI texels, for the fragment stage
  // RGBA32F, relief_levels levels: layer 0 the height (r) and the relief tone of each colour channel (gba),
  // layer 1 the relief normal (rgb, relief_normals.hpp) and its length (a), layers 2 and 3 the horizons of
  // azimuths 0-3 and 4-7 (relief_horizons.hpp; 0 where the material casts no shadows).
  std::unique_ptr<TextureArray> range_image;
  std::uint32_t mip_levels = 1;     // of the subspace images
  std::uint32_t relief_levels = 1;  // of the range texture (MaterialTablesHeader::relief_levels)
  bool shadows = false;
  bool hardware_filtering = false;
  std::uint32_t cost_probe = 0;  // MaterialBindingInfo::cost_probe
  PairCoupling pair_coupling = PairCoupling::product;
  UniqueHandle<VkSampler> sampler;
  UniqueHandle<VkDescriptorSetLayout> set_layout;
  UniqueHandle<VkDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;  // freed with the pool
};

MaterialTextures material_textures(const SubspaceSynthesizer& synthesizer, const Material& material) {
  MaterialTextures textures;
  textures.view = synthesizer.image_view();
  textures.mip_levels = synthesizer.mip_levels();
  textures.width = synthesizer.width();
  textures.height = synthesizer.height();
  textures.periodic_overlap = synthesizer.periodic_overlap();
  textures.layers.resize(material.subspaces.size());
  for (std::uint32_t s = 0; s < material.subspaces.size(); ++s) textures.layers[s] = synthesizer.layer_of(s);
  return textures;
}

Status MaterialBinding::create(Context& context, const Material& material, const MaterialTextures& textures,
                               const MaterialBindingInfo& info,
                               std::unique_ptr<MaterialBinding>& out) noexcept {
  try {
    if (textures.view == VK_NULL_HANDLE || textures.width == 0 || textures.height == 0) {
      return {ErrorCode::invalid_argument,
              "the material textures are empty: synthesize the subspace images first"};
    }
    const std::size_t pairs = material.lights.size() * material.views.size();
    if (!textures.pair_layers.empty() && textures.pair_layers.size() != pairs) {
      return {ErrorCode::invalid_argument,
              "the material textures give layers for " + std::to_string(textures.pair_layers.size()) +
                  " (light, view) pairs, the material has " + std::to_string(pairs)};
    }
    if (textures.pair_layers.empty() && textures.layers.size() != material.subspaces.size()) {
      return {ErrorCode::invalid_argument,
              "the material textures give layers for " + std::to_string(textures.layers.size()) +
                  " subspace images, the material has " + std::to_string(material.subspaces.size())};
    }
    if (!std::all_of(textures.layers.begin(), textures.layers.end(), fits_pair_table) ||
        !std::all_of(textures.pair_layers.begin(), textures.pair_layers.end(), fits_pair_table)) {
      return {ErrorCode::invalid_argument, "the material textures give a layer of 65535 or more"};
    }
    if (textures.mip_levels == 0 || textures.mip_levels > mip_level_count(textures.width, textures.height)) {
      return {ErrorCode::invalid_argument,
              "the material textures claim " + std::to_string(textures.mip_levels) + " mip levels; a " +
                  std::to_string(textures.width) + "x" + std::to_string(textures.height) +
                  " texture has 1 to " + std::to_string(mip_level_count(textures.width, textures.height))};
    }
    if (!std::isfinite(info.parallax_scale))
      return {ErrorCode::invalid_argument, "the parallax scale is not finite"};
    if (info.parallax_steps > kMaxParallaxSteps) {
      return {ErrorCode::invalid_argument, "the parallax march takes at most " +
                                               std::to_string(kMaxParallaxSteps) + " steps, not " +
                                               std::to_string(info.parallax_steps)};
    }
    std::unique_ptr<MaterialBinding> binding(new MaterialBinding());
    binding->context_ = &context;
    binding->resources_ = std::make_unique<Resources>();
    Resources& r = *binding->resources_;
    r.width = textures.width;
    r.height = textures.height;
    r.cost_probe = info.cost_probe;
    r.pair_coupling = info.pair_coupling;

    // Host side (material_tables.hpp): the tables and the relief.
    // The range map gets RangeTiles::chroma_levels levels more than the subspace images where its size
    // allows it, so that the relief's chroma can be read that far above its brightness at every level the
    // images have (carbtf_material_shade()); one level alone where the device cannot blit RGBA32F with a
    // linear filter.
    r.mip_levels = textures.mip_levels;
    if (info.max_mip_levels > 0) r.mip_levels = std::min(r.mip_levels, info.max_mip_levels);
    r.relief_levels = std::min(r.mip_levels + material.range.chroma_levels,
                               mip_level_count(textures.width, textures.height));
    if (!can_blit_mips(context, VK_FORMAT_R32G32B32A32_SFLOAT)) r.mip_levels = r.relief_levels = 1;
    const TextureWindow block{info.seed,      info.row0,       info.col0,
                              textures.width, textures.height, textures.periodic_overlap};
    ReliefMaps relief = relief_maps(material, block);
    const MaterialLayers layers{textures.layers, textures.pair_layers};
    CARBTF_TRY(
        build_material_tables(material, layers,
                              {textures.width, textures.height, relief.wrap, r.mip_levels, r.relief_levels,
                               info.parallax_scale, info.lookup_grid_size, info.parallax_steps},
                              relief, r.tables, r.pair_table));
    r.pair_layers = !textures.pair_layers.empty();
    r.shadows = material.range.shadow_scale > 0.0f;

    // GPU side: the tables as they are, the range texture's layers with their levels.
    CARBTF_TRY(Buffer::create(
        context,
        {r.tables.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
         MemoryUsage::host_upload, "carbtf material tables"},
        r.table_buffer));
    std::memcpy(r.table_buffer.mapped(), r.tables.data(), r.tables.size() * 4);
    // The levels come from here, not from blits: the normal layer's w holds each texel's own length.
    CARBTF_TRY(TextureArray::create(context, textures.width, textures.height, kRangeTextureLayers,
                                    VK_FORMAT_R32G32B32A32_SFLOAT, r.range_image, r.relief_levels, true));
    if (r.range_image->mip_levels() != r.relief_levels)
      return {ErrorCode::vulkan_error, "the range map did not get its mip levels"};
    CARBTF_TRY(set_range_layer(*r.range_image, 0, height_tone_texels(relief.heights, relief.tone), false));
    CARBTF_TRY(set_range_layer(
        *r.range_image, 1, normal_texels(relief.heights, relief.width, relief.height, relief.wrap), true));
    const std::vector<float> horizons = relief_horizon_map(relief, material.range.shadow_scale);
    std::vector<float> texels;
    for (std::uint32_t half = 0; half < 2; ++half) {
      horizon_layer(horizons, relief.heights.size(), half, texels);
      CARBTF_TRY(set_range_layer(*r.range_image, 2 + half, texels, false));
    }
    r.range_map = std::move(relief.heights);
    r.tone_map = std::move(relief.tone);

    const VulkanFunctions& vk = context.vk();
    const VkDevice device = context.device();
    // texelFetch ignores filtering. With hardware filtering the shader's textureLod() reads the subspace
    // images and the range texture (but its normals) through this sampler: trilinear over the levels the
    // binding uses, the edge texels repeated or, for periodic textures, the addresses wrapped, as the
    // hand filtering does.
    VkFormatProperties format{};
    vk.vkGetPhysicalDeviceFormatProperties(context.physical_device(), VK_FORMAT_R32G32B32A32_SFLOAT, &format);
    r.hardware_filtering =
        info.hardware_filtering &&
        (format.optimalTilingFeatures & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) != 0;
    auto sampler_info = vk_struct<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    sampler_info.magFilter = sampler_info.minFilter =
        r.hardware_filtering ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
    sampler_info.mipmapMode =
        r.hardware_filtering ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
    sampler_info.addressModeU = sampler_info.addressModeV = sampler_info.addressModeW =
        textures.periodic_overlap > 0 ? VK_SAMPLER_ADDRESS_MODE_REPEAT
                                      : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    sampler_info.minLod = 0.0f;
    sampler_info.maxLod = static_cast<float>(r.relief_levels - 1);  // each image view holds its own levels
    VkSampler sampler = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateSampler(device, &sampler_info, nullptr, &sampler));
    r.sampler = UniqueHandle<VkSampler>(&vk, device, sampler);
    context.set_debug_name(r.sampler, "carbtf material sampler");

    // The fragment stage reads the tables per pixel through a texel buffer view: on lavapipe a texel
    // fetch costs a fraction of a storage buffer read at a varying address (docs/design.md 4.5).
    // R32G32B32A32_UINT uniform texel buffers are mandatory; their length is not.
    VkPhysicalDeviceProperties properties{};
    vk.vkGetPhysicalDeviceProperties(context.physical_device(), &properties);
    const std::size_t quads = r.tables.size() / 4;
    if (quads > properties.limits.maxTexelBufferElements) {
      return {ErrorCode::device_unsuitable,
              "the material's lookup tables take " + std::to_string(quads) +
                  " texels, more than the device's " +
                  std::to_string(properties.limits.maxTexelBufferElements) +
                  " texel buffer elements (fewer directions or a smaller lookup_grid_size fit)"};
    }
    auto view_info = vk_struct<VkBufferViewCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO);
    view_info.buffer = r.table_buffer.handle();
    view_info.format = VK_FORMAT_R32G32B32A32_UINT;
    view_info.range = VK_WHOLE_SIZE;
    VkBufferView quads_view = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateBufferView(device, &view_info, nullptr, &quads_view));
    r.table_quads = UniqueHandle<VkBufferView>(&vk, device, quads_view);
    context.set_debug_name(r.table_quads, "carbtf material table quads");

    const VkShaderStageFlags stages = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
    const VkDescriptorSetLayoutBinding bindings[4] = {
        {gpu::CARBTF_MATERIAL_BINDING_SUBSPACES, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages,
         nullptr},
        {gpu::CARBTF_MATERIAL_BINDING_RANGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr},
        {gpu::CARBTF_MATERIAL_BINDING_TABLES, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr},
        {gpu::CARBTF_MATERIAL_BINDING_TABLE_QUADS, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1, stages,
         nullptr}};
    auto layout_info =
        vk_struct<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    layout_info.bindingCount = 4;
    layout_info.pBindings = bindings;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &set_layout));
    r.set_layout = UniqueHandle<VkDescriptorSetLayout>(&vk, device, set_layout);
    context.set_debug_name(r.set_layout, "carbtf material set layout");

    const VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 2},
                                           {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1},
                                           {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, 1}};
    auto pool_info = vk_struct<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    pool_info.maxSets = 1;
    pool_info.poolSizeCount = 3;
    pool_info.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    CARBTF_VK_TRY(vk.vkCreateDescriptorPool(device, &pool_info, nullptr, &pool));
    r.pool = UniqueHandle<VkDescriptorPool>(&vk, device, pool);
    context.set_debug_name(r.pool, "carbtf material descriptor pool");
    auto allocate = vk_struct<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
    allocate.descriptorPool = pool;
    allocate.descriptorSetCount = 1;
    allocate.pSetLayouts = &set_layout;
    CARBTF_VK_TRY(vk.vkAllocateDescriptorSets(device, &allocate, &r.set));

    const VkDescriptorImageInfo subspaces{sampler, textures.view, textures.layout};
    const VkDescriptorImageInfo range{sampler, r.range_image->view(),
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorBufferInfo tables{r.table_buffer.handle(), 0, VK_WHOLE_SIZE};
    const detail::DescriptorResource resources[4] = {
        {.type = bindings[0].descriptorType, .image = &subspaces},
        {.type = bindings[1].descriptorType, .image = &range},
        {.type = bindings[2].descriptorType, .buffer = &tables},
        {.type = bindings[3].descriptorType, .texel_buffer = &quads_view}};
    VkWriteDescriptorSet writes[4];
    for (int i = 0; i < 4; ++i)
      writes[i] = detail::descriptor_write(bindings[i].binding, resources[i], r.set);
    vk.vkUpdateDescriptorSets(device, 4, writes, 0, nullptr);
    out = std::move(binding);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while building the material binding"};
  }
}

MaterialBinding::~MaterialBinding() = default;

Status MaterialBinding::record_upload(VkCommandBuffer command_buffer) const noexcept {
  return resources_->range_image->record_upload(command_buffer);
}

std::uint32_t MaterialBinding::mip_levels() const noexcept {
  return resources_->mip_levels;
}

std::uint32_t MaterialBinding::relief_levels() const noexcept {
  return resources_->relief_levels;
}

bool MaterialBinding::casts_shadows() const noexcept {
  return resources_->shadows;
}

bool MaterialBinding::hardware_filtering() const noexcept {
  return resources_->hardware_filtering;
}

PairCoupling MaterialBinding::pair_coupling() const noexcept {
  return resources_->pair_coupling;
}

void MaterialBinding::shader_constants(MaterialShaderConstants& out) const noexcept {
  out.values = {casts_shadows() ? VK_TRUE : VK_FALSE, hardware_filtering() ? VK_TRUE : VK_FALSE,
                resources_->cost_probe,
                pair_coupling() == PairCoupling::staircase ? gpu::CARBTF_PAIR_COUPLING_STAIRCASE
                                                           : gpu::CARBTF_PAIR_COUPLING_PRODUCT};
  out.entries = {
      VkSpecializationMapEntry{CARBTF_SHADOWS_DEFAULT_CONSTANT_ID, 0, sizeof(VkBool32)},
      VkSpecializationMapEntry{CARBTF_HARDWARE_FILTERING_DEFAULT_CONSTANT_ID, 4, sizeof(VkBool32)},
      VkSpecializationMapEntry{CARBTF_COST_PROBE_DEFAULT_CONSTANT_ID, 8, sizeof(std::uint32_t)},
      VkSpecializationMapEntry{CARBTF_PAIR_COUPLING_DEFAULT_CONSTANT_ID, 12, sizeof(std::uint32_t)}};
  out.info = {static_cast<std::uint32_t>(out.entries.size()), out.entries.data(), sizeof out.values,
              out.values.data()};
}

Status MaterialBinding::upload_and_wait() noexcept {
  return context_->submit_and_wait([this](VkCommandBuffer cb) { return record_upload(cb); });
}

VkDescriptorSetLayout MaterialBinding::set_layout() const noexcept {
  return resources_->set_layout.get();
}
VkDescriptorSet MaterialBinding::set() const noexcept {
  return resources_->set;
}
std::uint32_t MaterialBinding::width() const noexcept {
  return resources_->width;
}
std::uint32_t MaterialBinding::height() const noexcept {
  return resources_->height;
}
Status MaterialBinding::set_layers(const Material& material, std::span<const std::uint32_t> layers) noexcept {
  Resources& r = *resources_;
  if (r.pair_layers)
    return {ErrorCode::invalid_argument, "this binding draws (light, view) pair layers, not subspace layers"};
  const std::size_t pairs = material.lights.size() * material.views.size();
  if (layers.size() != material.subspaces.size() || r.pair_table + 2 * pairs > r.tables.size()) {
    return {ErrorCode::invalid_argument,
            "set_layers() got " + std::to_string(layers.size()) + " subspace layers for a material of " +
                std::to_string(material.subspaces.size()) + " subspace images and " + std::to_string(pairs) +
                " (light, view) pairs: not the binding's material"};
  }
  if (!std::all_of(layers.begin(), layers.end(), fits_pair_table)) {
    return {ErrorCode::invalid_argument, "set_layers() got a layer of 65535 or more"};
  }
  MaterialLayers subspace_layers;
  subspace_layers.subspace_layers.assign(layers.begin(), layers.end());
  const std::span<std::uint32_t> table = std::span(r.tables).subspan(r.pair_table, 2 * pairs);
  write_pair_table(material, subspace_layers, table);
  std::memcpy(static_cast<std::uint32_t*>(r.table_buffer.mapped()) + r.pair_table, table.data(),
              table.size_bytes());
  return {};
}

const std::vector<std::uint32_t>& MaterialBinding::tables() const noexcept {
  return resources_->tables;
}
const std::vector<float>& MaterialBinding::range_map() const noexcept {
  return resources_->range_map;
}
const std::vector<float>& MaterialBinding::tone_map() const noexcept {
  return resources_->tone_map;
}

}  // namespace carbtf
