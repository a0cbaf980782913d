// Internal: reading RGBA32F image layers back to the host a band of rows at a time, so that a whole
// 4096^2 x 20 result does not need a second copy of the image on the host.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::detail {

// The host buffer a readback goes through unless the caller sets another size.
inline constexpr VkDeviceSize kDefaultReadbackBytes = VkDeviceSize{64} << 20;

// Submits `work` followed by the readback of the first band of rows of layers [0, layers) of `image` (in
// GENERAL, last written by compute shaders), then each further band on its own, each at most
// `band_bytes` (at least one row), through `readback` (created, or replaced when smaller than a band);
// `unpack(rgba, row0, rows)` receives each band, tightly packed layer by layer. The image is back in
// GENERAL afterwards.
Status read_back_in_row_bands(Context& context, VkImage image, std::uint32_t width, std::uint32_t height,
                              std::uint32_t layers, VkDeviceSize band_bytes, Buffer& readback,
                              const std::function<Status(VkCommandBuffer)>& work,
                              const std::function<void(const float*, std::uint32_t, std::uint32_t)>& unpack);

// Unpacks `pixels` RGBA texels into `out` from texel `first` on, keeping the first `channels`.
void unpack_rgba(const float* rgba, std::size_t pixels, std::uint32_t channels, std::size_t first,
                 std::vector<float>& out);

}  // namespace carbtf::detail
