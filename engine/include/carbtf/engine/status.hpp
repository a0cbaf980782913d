// Result codes of the carbtf engine API. No exception crosses the engine boundary: every fallible call
// returns a Status (or fills an out-parameter and returns one). Status is cheap to move; the message is
// one human-readable line naming what failed and, where it helps, what to do about it.
#pragma once

#include <string>
#include <utility>

namespace carbtf {

enum class ErrorCode {
  ok = 0,
  vulkan_loader_missing,     // libvulkan.so.1 could not be loaded
  vulkan_driver_missing,     // the loader found no driver (ICD) or no physical device
  validation_layer_missing,  // validation was requested but VK_LAYER_KHRONOS_validation is absent
  device_not_found,          // the device selector matched no device
  device_unsuitable,         // the device lacks a required version, queue, extension or feature
  invalid_argument,          // the caller passed something the API cannot use
  out_of_host_memory,
  out_of_device_memory,
  device_lost,
  vulkan_error,      // any other failing VkResult
  file_error,        // a file could not be read or written
  invalid_material,  // a material file or Material is malformed, truncated or hostile
};

class [[nodiscard]] Status {
 public:
  Status() = default;  // success
  Status(ErrorCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status success() { return {}; }

  bool ok() const noexcept { return code_ == ErrorCode::ok; }
  ErrorCode code() const noexcept { return code_; }
  const std::string& message() const noexcept { return message_; }

 private:
  ErrorCode code_ = ErrorCode::ok;
  std::string message_;
};

// A short stable name for an error code, e.g. "device_not_found".
const char* error_code_name(ErrorCode code) noexcept;

}  // namespace carbtf
