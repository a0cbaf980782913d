// Internal: turning failing VkResults into Status values that name the call, file and line.
#pragma once

#include <vulkan/vulkan.h>

#include "carbtf/engine/status.hpp"

namespace carbtf::detail {

const char* vk_result_name(VkResult result) noexcept;
Status vulkan_failure(VkResult result, const char* call, const char* file, int line);

}  // namespace carbtf::detail

// Evaluates a Vulkan call; on anything but VK_SUCCESS returns a Status from the enclosing function.
#define CARBTF_VK_TRY(call)                                                                 \
  do {                                                                                      \
    const VkResult carbtf_vk_result = (call);                                               \
    if (carbtf_vk_result != VK_SUCCESS)                                                     \
      return ::carbtf::detail::vulkan_failure(carbtf_vk_result, #call, __FILE__, __LINE__); \
  } while (0)

// Evaluates an expression yielding Status; returns it from the enclosing function when it failed.
#define CARBTF_TRY(expression)                     \
  do {                                             \
    ::carbtf::Status carbtf_status = (expression); \
    if (!carbtf_status.ok()) return carbtf_status; \
  } while (0)
