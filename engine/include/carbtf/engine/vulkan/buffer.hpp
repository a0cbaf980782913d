// GPU buffers and images that own their memory. One allocation per object: carbtf creates few, large
// objects, so a sub-allocator would buy nothing yet.
// Lifetime: destroy before the Context; do not destroy while a submitted command buffer still uses it.
// Thread safety: externally synchronized.
#pragma once

#include <cstdint>

#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf {

enum class MemoryUsage {
  device_local,   // GPU-only
  host_readback,  // host-visible, cached where possible; persistently mapped
  host_upload,    // host-visible, coherent; persistently mapped
};

struct BufferCreateInfo {
  VkDeviceSize size = 0;  // bytes, > 0
  VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  MemoryUsage memory = MemoryUsage::device_local;
  const char* debug_name = "carbtf buffer";
};

class Buffer {
 public:
  Buffer() = default;
  static Status create(const Context& context, const BufferCreateInfo& info, Buffer& out) noexcept;

  VkBuffer handle() const noexcept { return buffer_.get(); }
  VkDeviceSize size() const noexcept { return size_; }
  // Host pointer to the whole buffer for host-visible memory, else null. Valid for the buffer's life.
  void* mapped() const noexcept { return mapped_; }
  // Makes device writes visible to the host (needed for non-coherent memory; cheap otherwise).
  Status invalidate_for_host_read() const noexcept;

 private:
  const Context* context_ = nullptr;
  UniqueHandle<VkBuffer> buffer_;
  UniqueHandle<VkDeviceMemory> memory_;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  bool coherent_ = true;
};

struct ImageCreateInfo {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t array_layers = 1;
  std::uint32_t mip_levels = 1;  // the view covers all of them
  VkFormat format = VK_FORMAT_R32_SFLOAT;
  VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  const char* debug_name = "carbtf image";
};

// A 2D (array) image in device-local memory, optimal tiling, created in VK_IMAGE_LAYOUT_UNDEFINED,
// with a view of all its layers (VK_IMAGE_VIEW_TYPE_2D_ARRAY); the depth aspect for D32_SFLOAT and
// D16_UNORM, else the colour aspect.
class Image {
 public:
  Image() = default;
  static Status create(const Context& context, const ImageCreateInfo& info, Image& out) noexcept;

  VkImage handle() const noexcept { return image_.get(); }
  VkImageView view() const noexcept { return view_.get(); }
  // A view of level 0 alone, all layers: what a storage-image descriptor needs (one level). The same
  // as view() for an image of one level.
  VkImageView level0_view() const noexcept { return level0_view_ ? level0_view_.get() : view_.get(); }
  const ImageCreateInfo& info() const noexcept { return info_; }

 private:
  // Declaration order is destruction order reversed: the view goes before the image.
  UniqueHandle<VkDeviceMemory> memory_;
  UniqueHandle<VkImage> image_;
  UniqueHandle<VkImageView> view_;
  UniqueHandle<VkImageView> level0_view_;  // only with more than one level
  ImageCreateInfo info_{};
};

}  // namespace carbtf
