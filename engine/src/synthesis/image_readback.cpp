#include "synthesis/image_readback.hpp"

#include <algorithm>

#include "vulkan/barriers.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf::detail {
namespace {

void record_image_readback(const VulkanFunctions& vk, VkCommandBuffer command_buffer, VkImage image,
                           std::uint32_t width, std::uint32_t row0, std::uint32_t rows, std::uint32_t layers,
                           VkBuffer destination) {
  const ColourRange all{0, 1, 0, layers};
  transition_colour(vk, command_buffer, image, all, VK_IMAGE_LAYOUT_GENERAL,
                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT},
                    {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT});
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, layers};
  copy.imageOffset = {0, static_cast<std::int32_t>(row0), 0};
  copy.imageExtent = {width, rows, 1};
  vk.vkCmdCopyImageToBuffer(command_buffer, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, destination, 1,
                            &copy);
  // A read needs no availability, only ordering before later writes.
  transition_colour(
      vk, command_buffer, image, all, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL,
      {VK_PIPELINE_STAGE_TRANSFER_BIT, 0},
      {VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT});
  memory_barrier(vk, command_buffer, {VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT},
                 {VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT});
}

}  // namespace

void unpack_rgba(const float* rgba, std::size_t pixels, std::uint32_t channels, std::size_t first,
                 std::vector<float>& out) {
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::uint32_t c = 0; c < channels; ++c) out[(first + p) * channels + c] = rgba[p * 4 + c];
  }
}

Status read_back_in_row_bands(Context& context, VkImage image, std::uint32_t width, std::uint32_t height,
                              std::uint32_t layers, VkDeviceSize band_bytes, Buffer& readback,
                              const std::function<Status(VkCommandBuffer)>& work,
                              const std::function<void(const float*, std::uint32_t, std::uint32_t)>& unpack) {
  const VkDeviceSize row_bytes = VkDeviceSize{width} * 4 * sizeof(float) * layers;
  const auto band_rows =
      static_cast<std::uint32_t>(std::clamp<VkDeviceSize>(band_bytes / row_bytes, 1, height));
  if (readback.handle() == VK_NULL_HANDLE || readback.size() < row_bytes * band_rows) {
    readback = {};  // released before the new one is allocated
    CARBTF_TRY(Buffer::create(context,
                              {row_bytes * band_rows, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                               MemoryUsage::host_readback, "carbtf readback"},
                              readback));
  }
  for (std::uint32_t row0 = 0; row0 < height; row0 += band_rows) {
    const std::uint32_t rows = std::min(band_rows, height - row0);
    const auto record_band = [&](VkCommandBuffer command_buffer) -> Status {
      if (row0 == 0) CARBTF_TRY(work(command_buffer));
      record_image_readback(context.vk(), command_buffer, image, width, row0, rows, layers,
                            readback.handle());
      return {};
    };
    CARBTF_TRY(context.submit_and_wait(record_band));
    CARBTF_TRY(readback.invalidate_for_host_read());
    unpack(static_cast<const float*>(readback.mapped()), row0, rows);
  }
  return {};
}

}  // namespace carbtf::detail
