// carbtf_parallax_uv() (compute_shaders/include/carbtf_material.glsl) on the CPU, in the shader's float
// arithmetic and order: the texture point that the ray from the eye through the plane point uv meets
// first, marched down from the relief's top to its bottom (ReliefExtent) at most
// kParallaxStepTexels across or down per step and `steps` steps, then refined between the last
// point above the relief and the first below it, and the chord's crossing taken. `steps` 0: offset
// mapping, uv shifted by the height at uv times view.xy. The render reference and the analysis (which
// maps the render's pixels to texels the same way) share it.
//
// height_at(uv): the height at uv minus the relief's mean, in texels (unscaled); size: the texture's
// texels; view: unit, tangent frame (x along +u, y towards row 0), towards the eye.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "carbtf/engine/render/material_tables.hpp"

namespace carbtf::reference {

template <typename HeightAt>
glm::vec2 parallax_march(const HeightAt& height_at, glm::vec2 uv, glm::vec3 view, glm::vec2 size,
                         float parallax_scale, const ReliefExtent& extent, std::uint32_t steps) {
  const glm::vec2 uv_per_t = glm::vec2(view.x, -view.y) / size;  // texture up is -v
  if (steps == 0) return uv + parallax_scale * height_at(uv) * uv_per_t;
  const float across = glm::length(glm::vec2(view.x, view.y));
  const float view_z = std::max(view.z, kParallaxMinViewZ);
  float t_above = extent.top / view_z;
  float t_below = extent.bottom / view_z;
  const float span = t_above - t_below;
  if (!(span > 0.0f) || across == 0.0f) return uv;  // a flat relief, or a view straight down
  // How far the ray runs above the relief at parameter t (texels along the view from the plane).
  const auto clearance = [&](float t) { return t * view_z - parallax_scale * height_at(uv + t * uv_per_t); };
  const auto wanted =
      static_cast<std::uint32_t>(std::ceil(span * std::max(across, view_z) / kParallaxStepTexels));
  const std::uint32_t taken = std::clamp(wanted, 1u, steps);
  const float dt = span / static_cast<float>(taken);
  const float top = t_above;
  float f_above = clearance(t_above);
  float f_below = 0.0f;
  for (std::uint32_t i = 1; i <= taken; ++i) {
    const float t = top - static_cast<float>(i) * dt;
    const float f = clearance(t);
    if (f <= 0.0f || i == taken) {
      t_below = t;
      f_below = f;
      break;
    }
    t_above = t;
    f_above = f;
  }
  for (std::uint32_t i = 0; i < kParallaxRefinements; ++i) {
    const float t = 0.5f * (t_above + t_below);
    const float f = clearance(t);
    if (f > 0.0f) {
      t_above = t;
      f_above = f;
    } else {
      t_below = t;
      f_below = f;
    }
  }
  const float t = f_above > f_below ? t_above - f_above * (t_above - t_below) / (f_above - f_below) : t_below;
  return uv + t * uv_per_t;
}

}  // namespace carbtf::reference
