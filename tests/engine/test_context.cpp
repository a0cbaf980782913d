// The Vulkan context: device listing and selection, validation reporting, RAII objects.
#include <catch2/catch.hpp>

#include <cstdlib>

#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/engine/vulkan/gpu_timer.hpp"
#include "test_support.hpp"

using namespace carbtf;

TEST_CASE("devices are listed and the default one is suitable", "[engine]") {
  std::vector<DeviceInfo> devices;
  const Status status = enumerate_devices(devices);
  INFO(status.message());
  REQUIRE(status.ok());
  REQUIRE(!devices.empty());
  std::uint32_t chosen = 99;
  REQUIRE(select_device(devices, "", chosen).ok());
  REQUIRE(chosen < devices.size());
  CHECK(devices[chosen].suitable);
  CHECK(devices[chosen].max_storage_buffer_range > 0);
}

TEST_CASE("device selectors pick by index or name and reject what matches nothing", "[engine]") {
  std::vector<DeviceInfo> devices(2);
  devices[0].index = 0;
  devices[0].name = "llvmpipe (LLVM 15)";
  devices[0].type = VK_PHYSICAL_DEVICE_TYPE_CPU;
  devices[0].suitable = true;
  devices[1].index = 1;
  devices[1].name = "NVIDIA H100";
  devices[1].type = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
  devices[1].suitable = true;
  std::uint32_t chosen = 99;

  REQUIRE(select_device(devices, "", chosen).ok());
  CHECK(chosen == 1);  // the discrete GPU wins by default
  REQUIRE(select_device(devices, "0", chosen).ok());
  CHECK(chosen == 0);
  REQUIRE(select_device(devices, "LLVMPIPE", chosen).ok());
  CHECK(chosen == 0);

  const Status missing = select_device(devices, "radeon", chosen);
  CHECK(missing.code() == ErrorCode::device_not_found);
  CHECK_THAT(missing.message(), Catch::Contains("radeon") && Catch::Contains("llvmpipe"));
  CHECK(select_device(devices, "7", chosen).code() == ErrorCode::device_not_found);

  devices[1].suitable = false;
  devices[1].unsuitable_reason = "lacks VK_KHR_push_descriptor";
  const Status unsuitable = select_device(devices, "nvidia", chosen);
  CHECK(unsuitable.code() == ErrorCode::device_unsuitable);
  CHECK_THAT(unsuitable.message(), Catch::Contains("VK_KHR_push_descriptor"));
  REQUIRE(select_device(devices, "", chosen).ok());
  CHECK(chosen == 0);
}

TEST_CASE("CARBTF_DEVICE picks the device when no selector is given", "[engine]") {
  REQUIRE(setenv("CARBTF_DEVICE", "no-such-device", 1) == 0);
  std::unique_ptr<Context> context;
  ContextCreateInfo info;
  const Status status = Context::create(info, context);
  unsetenv("CARBTF_DEVICE");
  CHECK(status.code() == ErrorCode::device_not_found);
  CHECK_THAT(status.message(), Catch::Contains("CARBTF_DEVICE") && Catch::Contains("no-such-device"));
  CHECK(context == nullptr);
}

TEST_CASE("a deliberate validation error is caught by the messenger", "[engine][validation]") {
  ContextCreateInfo info;
  info.enable_validation = true;
  int callback_errors = 0;
  info.on_message = [&](MessageSeverity severity, const char*) {
    callback_errors += severity == MessageSeverity::error;
  };
  std::unique_ptr<Context> context;
  REQUIRE(Context::create(info, context).ok());
  REQUIRE(context->validation_report().clean());

  // A buffer with no usage flags violates VUID-VkBufferCreateInfo-usage-requiredbitmask.
  auto create = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  create.size = 256;
  create.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = context->vk().vkCreateBuffer(context->device(), &create, nullptr, &buffer);
  if (result == VK_SUCCESS) context->vk().vkDestroyBuffer(context->device(), buffer, nullptr);

  const ValidationReport report = context->validation_report();
  CHECK(report.errors >= 1);
  CHECK(callback_errors >= 1);
  REQUIRE(!report.messages.empty());
  CHECK_THAT(report.messages.front(), Catch::Contains("VkBufferCreateInfo-usage"));
}

TEST_CASE("buffers, images and timers are created, named and destroyed cleanly", "[engine][validation]") {
  test::ValidatedContext context;
  Buffer device_buffer, readback;
  REQUIRE(Buffer::create(*context,
                         {1 << 20, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::device_local, "test"},
                         device_buffer)
              .ok());
  REQUIRE(Buffer::create(*context,
                         {4096, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::host_readback, "readback"},
                         readback)
              .ok());
  CHECK(device_buffer.size() == (1 << 20));
  REQUIRE(readback.mapped() != nullptr);
  Image image;
  REQUIRE(Image::create(*context, {64, 32, 2}, image).ok());
  CHECK(image.handle() != VK_NULL_HANDLE);

  // Move semantics: the moved-from buffer no longer owns anything; only one destroy happens.
  Buffer moved = std::move(device_buffer);
  CHECK(moved.handle() != VK_NULL_HANDLE);
  CHECK(device_buffer.handle() == VK_NULL_HANDLE);

  GpuTimer timer;
  REQUIRE(GpuTimer::create(*context, 2, timer).ok());
  REQUIRE(context
              ->submit_and_wait([&](VkCommandBuffer cmd) {
                timer.record_reset(cmd);
                timer.record_timestamp(cmd, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
                context->vk().vkCmdFillBuffer(cmd, readback.handle(), 0, 4096, 0x3f800000u);
                timer.record_timestamp(cmd, 1, VK_PIPELINE_STAGE_TRANSFER_BIT);
                auto barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
                barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
                context->vk().vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                                   VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0, nullptr, 0,
                                                   nullptr);
                return Status{};
              })
              .ok());
  REQUIRE(readback.invalidate_for_host_read().ok());
  CHECK(static_cast<const float*>(readback.mapped())[1023] == 1.0f);
  double ms = -1;
  REQUIRE(timer.elapsed_ms(0, 1, ms).ok());
  CHECK(ms >= 0);
  CHECK(timer.elapsed_ms(0, 2, ms).code() == ErrorCode::invalid_argument);
  CHECK(Buffer::create(*context, {0}, readback).code() == ErrorCode::invalid_argument);
  context.require_clean();
}

TEST_CASE("a failing recording callback is reported and nothing is submitted", "[engine][validation]") {
  test::ValidatedContext context;
  const Status status = context->submit_and_wait(
      [](VkCommandBuffer) { return Status(ErrorCode::invalid_argument, "recording refused"); });
  CHECK(status.code() == ErrorCode::invalid_argument);
  CHECK(status.message() == "recording refused");
  // The context stays usable.
  CHECK(context->submit_and_wait([](VkCommandBuffer) { return Status{}; }).ok());
  context.require_clean();
}
