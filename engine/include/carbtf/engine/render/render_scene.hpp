// What one draw of carbtf's render pass shows: camera, lights and model transform. Plain data, with no
// Vulkan type, so that the CPU render reference (carbtf::reference) and the GPU render pass
// (mesh_renderer.hpp) take the same scene.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "carbtf/engine/status.hpp"

namespace carbtf {

// The most lights one draw shades with: the size of the shaders' light arrays (CARBTF_RENDER_MAX_LIGHTS in
// carbtf_gpu_shared.h, checked equal where the renderer is built). A scene with more is refused, not
// cut: MeshRenderer::record()/render() and ScenePruner::needs() return invalid_argument, and the CPU
// render reference throws std::invalid_argument, each naming the count and the limit.
inline constexpr std::uint32_t kMaxRenderLights = 4;

struct RenderLight {
  bool point = false;                      // false: directional
  std::array<float, 3> position{0, 0, 1};  // point: world position; directional: direction towards the light
  std::array<float, 3> colour{1, 1, 1};    // linear scale of the material's measured radiance
};

struct RenderCamera {
  std::array<float, 3> eye{2.2f, 2.2f, 1.8f};
  std::array<float, 3> target{0, 0, 0};
  std::array<float, 3> up{0, 0, 1};
  float fov_y_degrees = 40.0f;  // 0: orthographic, ortho_height world units tall
  float ortho_height = 2.2f;
  float near_plane = 0.05f;
  float far_plane = 100.0f;
};

struct RenderScene {
  RenderCamera camera;
  std::vector<RenderLight> lights;  // at most kMaxRenderLights
  // Object -> world, column-major; rotation, translation and uniform scale only.
  std::array<float, 16> model{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

// Success, or invalid_argument naming the scene's light count and kMaxRenderLights.
inline Status check_render_lights(const RenderScene& scene) {
  if (scene.lights.size() <= kMaxRenderLights) return {};
  return {ErrorCode::invalid_argument, "the scene has " + std::to_string(scene.lights.size()) +
                                           " lights; a draw shades with at most " +
                                           std::to_string(kMaxRenderLights) + " (kMaxRenderLights)"};
}

// The camera's world -> clip matrix (Vulkan clip space: y down, depth in [0, 1]), column-major.
std::array<float, 16> view_projection(const RenderCamera& camera, float aspect);

}  // namespace carbtf
