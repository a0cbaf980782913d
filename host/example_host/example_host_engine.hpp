// A minimal host engine that embeds carbtf as a material module, as a real Vulkan engine would: it
// creates its own instance, device, queue, command buffers, render pass and pipeline, and hands carbtf
// only its handles (Context::adopt). carbtf synthesizes the material into the host's command buffer
// and gives it a descriptor set; the host's own fragment shader (shaders/host_mesh_fragment.frag) includes
// carbtf_material.glsl and draws the material on the host's mesh in the host's render pass.
// `carbtf_example_host` runs its render loop; tests/host/test_embedding.cpp runs it headless.
// Errors throw std::runtime_error naming the failing call (it is an example program, not the engine).
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/vulkan/context.hpp"

namespace carbtf::example {

struct HostView {
  std::array<float, 3> eye{0.0f, -1.6f, 2.2f};
  std::array<float, 3> light{0.3f, 0.5f, 0.8f};  // direction towards the light, world
};

class ExampleHostEngine {
 public:
  // A headless engine with an RGBA32F colour target of width x height; `validation` enables the
  // Khronos validation layer and counts its messages (messages()).
  ExampleHostEngine(std::uint32_t width, std::uint32_t height, bool validation);
  ~ExampleHostEngine();
  ExampleHostEngine(const ExampleHostEngine&) = delete;
  ExampleHostEngine& operator=(const ExampleHostEngine&) = delete;

  // What carbtf needs to adopt this engine's device.
  AdoptInfo adopt_info() const;
  // Loads one material: carbtf adopts the device, synthesizes every subspace image of
  // texture_size^2 and uploads the range map, all recorded into the host's own command buffer.
  void load_material(const Material& material, std::uint32_t texture_size, std::uint64_t seed);
  // Draws the mesh with the material in the host's own render pass and reads the frame back
  // (width * height RGBA floats, row 0 at the top).
  std::vector<float> draw(const Mesh& mesh, const HostView& view);
  // Releases carbtf (every object it created), keeping the host's own objects.
  void unload_material();

  Context* carbtf_context() const { return context_.get(); }
  const MaterialBinding* binding() const { return binding_.get(); }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  // Validation-layer warnings and errors seen by the host's own messenger.
  const std::vector<std::string>& messages() const { return messages_; }
  // Whether the host's device is still usable (after carbtf is gone): a no-op submit succeeds.
  bool device_alive();

 private:
  struct Target;
  void create_device(bool validation);
  void create_target();
  void create_pipeline();
  void submit(const std::function<void(VkCommandBuffer)>& record);
  std::uint32_t memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) const;

  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  std::vector<std::string> messages_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer command_buffer_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  std::unique_ptr<Target> target_;

  std::unique_ptr<Context> context_;
  std::unique_ptr<SubspaceSynthesizer> synthesizer_;
  std::unique_ptr<MaterialBinding> binding_;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;  // set 0: the host's frame; set 1: carbtf's material
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace carbtf::example
