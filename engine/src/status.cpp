#include "carbtf/engine/status.hpp"

namespace carbtf {

const char* error_code_name(ErrorCode code) noexcept {
  switch (code) {
    case ErrorCode::ok:
      return "ok";
    case ErrorCode::vulkan_loader_missing:
      return "vulkan_loader_missing";
    case ErrorCode::vulkan_driver_missing:
      return "vulkan_driver_missing";
    case ErrorCode::validation_layer_missing:
      return "validation_layer_missing";
    case ErrorCode::device_not_found:
      return "device_not_found";
    case ErrorCode::device_unsuitable:
      return "device_unsuitable";
    case ErrorCode::invalid_argument:
      return "invalid_argument";
    case ErrorCode::out_of_host_memory:
      return "out_of_host_memory";
    case ErrorCode::out_of_device_memory:
      return "out_of_device_memory";
    case ErrorCode::device_lost:
      return "device_lost";
    case ErrorCode::vulkan_error:
      return "vulkan_error";
    case ErrorCode::file_error:
      return "file_error";
    case ErrorCode::invalid_material:
      return "invalid_material";
  }
  return "unknown";
}

}  // namespace carbtf
