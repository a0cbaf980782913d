#include "vulkan/vk_check.hpp"

#include <cstring>
#include <string>

namespace carbtf {

namespace detail {

const char* vk_result_name(VkResult result) noexcept {
  switch (result) {
#define CARBTF_RESULT_CASE(name) \
  case name:                     \
    return #name;
    CARBTF_RESULT_CASE(VK_SUCCESS)
    CARBTF_RESULT_CASE(VK_NOT_READY)
    CARBTF_RESULT_CASE(VK_TIMEOUT)
    CARBTF_RESULT_CASE(VK_INCOMPLETE)
    CARBTF_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    CARBTF_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    CARBTF_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    CARBTF_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    CARBTF_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    CARBTF_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    CARBTF_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    CARBTF_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    CARBTF_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    CARBTF_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    CARBTF_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    CARBTF_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    CARBTF_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    CARBTF_RESULT_CASE(VK_ERROR_UNKNOWN)
#undef CARBTF_RESULT_CASE
    default:
      return "VkResult";
  }
}

Status vulkan_failure(VkResult result, const char* call, const char* file, int line) {
  // Report paths from the source root ("engine/src/x.cpp"), not the build machine's absolute path.
  const char* short_file = std::strstr(file, "engine/");
  std::string message = std::string(call) + " failed with " + vk_result_name(result) + " (" +
                        std::to_string(static_cast<int>(result)) + ") at " +
                        (short_file ? short_file : file) + ":" + std::to_string(line);
  ErrorCode code = ErrorCode::vulkan_error;
  if (result == VK_ERROR_OUT_OF_HOST_MEMORY) code = ErrorCode::out_of_host_memory;
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY) code = ErrorCode::out_of_device_memory;
  if (result == VK_ERROR_DEVICE_LOST) code = ErrorCode::device_lost;
  return {code, std::move(message)};
}

}  // namespace detail

}  // namespace carbtf
