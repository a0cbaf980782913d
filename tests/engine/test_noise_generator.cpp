// GPU Gaussian noise against the CPU float32 reference: bit for bit.
#include <catch2/catch.hpp>

#include "carbtf/engine/synthesis/noise_generator.hpp"
#include "carbtf/engine/vulkan/buffer.hpp"
#include "carbtf/reference/noise.hpp"
#include "test_support.hpp"

using namespace carbtf;

namespace {

std::vector<float> cpu_block(const NoiseBlock& b) {
  std::vector<float> values(std::size_t{b.width} * b.height);
  // The field's coordinates are taken modulo 2^32 (noise_block.hpp), as the GPU takes them.
  reference::fill_noise_block(b.seed, b.field_id, static_cast<std::int32_t>(b.row0),
                              static_cast<std::int32_t>(b.col0), b.width, b.height, values);
  return values;
}

}  // namespace

TEST_CASE("GPU noise 1024x1024 is bit-identical to the CPU float32 reference", "[engine][noise][gpu]") {
  test::ValidatedContext context;
  std::unique_ptr<NoiseGenerator> generator;
  REQUIRE(NoiseGenerator::create(*context, generator).ok());
  const NoiseBlock block{7, 0, 0, 0, 1024, 1024};
  std::vector<float> gpu;
  const Status status = generator->generate(block, gpu);
  INFO(status.message());
  REQUIRE(status.ok());
  test::require_bitwise_equal(gpu, cpu_block(block), block.width);
  context.require_clean();
}

TEST_CASE("GPU noise blocks with odd sizes, negative origins and 64-bit seeds match the CPU",
          "[engine][noise][gpu]") {
  test::ValidatedContext context;
  std::unique_ptr<NoiseGenerator> generator;
  REQUIRE(NoiseGenerator::create(*context, generator).ok());
  for (const NoiseBlock block :
       {NoiseBlock{0xfedcba9876543210ull, 17, -64, -3, 33, 7},
        NoiseBlock{1, 0xffffffffu, 2147483000, -2147483600, 1, 1000}, NoiseBlock{42, 5, 3, 1, 777, 1}}) {
    std::vector<float> gpu;
    REQUIRE(generator->generate(block, gpu).ok());
    test::require_bitwise_equal(gpu, cpu_block(block), block.width);
  }
  context.require_clean();
}

TEST_CASE("a block split over many dispatches equals one dispatch", "[engine][noise][gpu]") {
  test::ValidatedContext context;
  std::unique_ptr<NoiseGenerator> generator;
  REQUIRE(NoiseGenerator::create(*context, generator).ok());
  // 3 rows of 75 floats per dispatch: chunk offsets are not multiples of the storage-offset alignment.
  const NoiseBlock block{9, 2, -5, 0, 75, 40};
  std::vector<float> whole, split;
  REQUIRE(generator->generate(block, whole).ok());
  generator->set_max_rows_per_dispatch(3);
  REQUIRE(generator->generate(block, split).ok());
  test::require_bitwise_equal(split, whole, block.width);
  test::require_bitwise_equal(split, cpu_block(block), block.width);
  context.require_clean();
}

TEST_CASE("noise recorded into the caller's command buffer lands at the caller's offset",
          "[engine][noise][gpu]") {
  test::ValidatedContext context;
  std::unique_ptr<NoiseGenerator> generator;
  REQUIRE(NoiseGenerator::create(*context, generator).ok());
  const NoiseBlock block{3, 1, 10, 20, 64, 64};
  const VkDeviceSize lead_floats = 13;  // unaligned on purpose: the generator must handle it
  Buffer buffer;
  REQUIRE(Buffer::create(*context,
                         {(lead_floats + 64 * 64 + 8) * sizeof(float),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          MemoryUsage::host_readback, "caller buffer"},
                         buffer)
              .ok());
  const float sentinel = -1234.5f;
  std::uint32_t sentinel_bits = 0;
  std::memcpy(&sentinel_bits, &sentinel, sizeof sentinel_bits);
  REQUIRE(context
              ->submit_and_wait([&](VkCommandBuffer cmd) -> Status {
                const VulkanFunctions& vk = context->vk();
                vk.vkCmdFillBuffer(cmd, buffer.handle(), 0, VK_WHOLE_SIZE, sentinel_bits);
                auto barrier = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
                barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
                barrier.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                                        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &barrier, 0, nullptr, 0,
                                        nullptr);
                if (Status s = generator->record(cmd, block, buffer.handle(), lead_floats * sizeof(float));
                    !s.ok())
                  return s;
                barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
                barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
                vk.vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                                        0, 1, &barrier, 0, nullptr, 0, nullptr);
                return {};
              })
              .ok());
  REQUIRE(buffer.invalidate_for_host_read().ok());
  const float* data = static_cast<const float*>(buffer.mapped());
  std::vector<float> written(data + lead_floats, data + lead_floats + 64 * 64);
  test::require_bitwise_equal(written, cpu_block(block), 64);
  for (VkDeviceSize i = 0; i < lead_floats; ++i) CHECK(data[i] == sentinel);
  for (VkDeviceSize i = lead_floats + 64 * 64; i < lead_floats + 64 * 64 + 8; ++i) CHECK(data[i] == sentinel);

  CHECK(generator->record(VK_NULL_HANDLE, block, buffer.handle(), 2).code() == ErrorCode::invalid_argument);
  context.require_clean();
}
