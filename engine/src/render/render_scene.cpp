#include "carbtf/engine/render/render_scene.hpp"

#include <cstring>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace carbtf {

namespace {

glm::vec3 vec3_of(const std::array<float, 3>& a) {
  return {a[0], a[1], a[2]};
}

}  // namespace

std::array<float, 16> view_projection(const RenderCamera& camera, float aspect) {
  const glm::mat4 view = glm::lookAtRH(vec3_of(camera.eye), vec3_of(camera.target), vec3_of(camera.up));
  glm::mat4 projection;
  if (camera.fov_y_degrees > 0.0f) {
    projection = glm::perspectiveRH_ZO(glm::radians(camera.fov_y_degrees), aspect, camera.near_plane,
                                       camera.far_plane);
  } else {
    const float h = 0.5f * camera.ortho_height, w = h * aspect;
    projection = glm::orthoRH_ZO(-w, w, -h, h, camera.near_plane, camera.far_plane);
  }
  projection[1][1] = -projection[1][1];  // Vulkan's clip-space y points down
  const glm::mat4 m = projection * view;
  std::array<float, 16> out;
  std::memcpy(out.data(), glm::value_ptr(m), sizeof out);
  return out;
}

}  // namespace carbtf
