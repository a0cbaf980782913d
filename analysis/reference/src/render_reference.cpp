#include "carbtf/reference/render_reference.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <glm/glm.hpp>

#include "carbtf/engine/material/material_directions.hpp"

namespace carbtf::reference {

namespace {

struct Sampler {
  const ReferenceRenderInput& input;
  std::uint32_t width, height;
  float range_mean;

  struct Bilinear {
    int x0, y0, x1, y1;
    float fx, fy;
  };
  Bilinear bilinear(glm::vec2 uv) const {
    const glm::vec2 u = input.wrap ? uv - glm::floor(uv) : uv;
    const glm::vec2 t = u * glm::vec2(static_cast<float>(width), static_cast<float>(height)) - 0.5f;
    const glm::vec2 base = glm::floor(t);
    const int w = static_cast<int>(width), h = static_cast<int>(height);
    const int ix = static_cast<int>(std::clamp(base.x, -1.0f, static_cast<float>(w)));
    const int iy = static_cast<int>(std::clamp(base.y, -1.0f, static_cast<float>(h)));
    if (input.wrap) {
      return {ix < 0 ? w - 1 : ix, iy < 0 ? h - 1 : iy, ix + 1 >= w ? 0 : ix + 1, iy + 1 >= h ? 0 : iy + 1,
              t.x - base.x, t.y - base.y};
    }
    return {std::clamp(ix, 0, w - 1),
            std::clamp(iy, 0, h - 1),
            std::clamp(ix + 1, 0, w - 1),
            std::clamp(iy + 1, 0, h - 1),
            t.x - base.x,
            t.y - base.y};
  }
  static float bilinear_at(std::span<const float> map, std::uint32_t width, const Bilinear& b) {
    auto at = [&](int x, int y) { return map[static_cast<std::size_t>(y) * width + x]; };
    const float top = glm::mix(at(b.x0, b.y0), at(b.x1, b.y0), b.fx);
    const float bottom = glm::mix(at(b.x0, b.y1), at(b.x1, b.y1), b.fx);
    return glm::mix(top, bottom, b.fy);
  }
  float height_at(glm::vec2 uv) const { return bilinear_at(input.range_map, width, bilinear(uv)) - range_mean; }
  float tone_at(const Bilinear& b) const { return input.tone_map.empty() ? 1.0f : bilinear_at(input.tone_map, width, b); }
  glm::vec3 subspace_at(const Bilinear& b, std::uint32_t subspace) const {
    const auto& image = input.images->images[subspace];
    const std::uint32_t channels = input.images->channels[subspace];
    auto at = [&](int x, int y) {
      glm::vec3 c(0.0f);
      const std::size_t base = (static_cast<std::size_t>(y) * width + x) * channels;
      for (std::uint32_t k = 0; k < std::min(channels, 3u); ++k) c[static_cast<int>(k)] = image[base + k];
      return c;
    };
    const glm::vec3 top = glm::mix(at(b.x0, b.y0), at(b.x1, b.y0), b.fx);
    const glm::vec3 bottom = glm::mix(at(b.x0, b.y1), at(b.x1, b.y1), b.fx);
    return glm::mix(top, bottom, b.fy);
  }
};

void angles(glm::vec3 d, double& theta, double& phi) {
  theta =
      std::atan2(std::hypot(static_cast<double>(d.x), static_cast<double>(d.y)), static_cast<double>(d.z));
  phi = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x));
}

}  // namespace

std::vector<float> render_plane(const ReferenceRenderInput& input, const RenderScene& scene,
                                std::uint32_t width, std::uint32_t height, std::array<float, 4> clear) {
  if (input.material == nullptr || input.images == nullptr || input.images->width == 0) {
    throw std::invalid_argument("render_plane: no material or subspace images");
  }
  const Material& material = *input.material;
  const std::uint32_t tw = input.images->width, th = input.images->height;
  if (input.range_map.size() != std::size_t{tw} * th) {
    throw std::invalid_argument("render_plane: the range map is not the subspace images' size");
  }
  if (!input.tone_map.empty() && input.tone_map.size() != input.range_map.size()) {
    throw std::invalid_argument("render_plane: the relief tone is not the range map's size");
  }
  MaterialDirections directions;
  if (const Status s = MaterialDirections::build(material, directions); !s.ok()) {
    throw std::invalid_argument("render_plane: the material's directions: " + s.message());
  }
  const float light_z_floor = relight_floor(material);
  // The mean in double, as the binding computes it.
  const double sum = std::accumulate(input.range_map.begin(), input.range_map.end(), 0.0);
  const Sampler sampler{input, tw, th, static_cast<float>(sum / static_cast<double>(input.range_map.size()))};

  const std::array<float, 16> vp =
      view_projection(scene.camera, static_cast<float>(width) / static_cast<float>(height));
  // Rays in double: unprojecting to a far plane 100 units away in float would move the hit point by
  // 1e-5, a thousandth of a texel, more than the GPU's own interpolation error.
  glm::dmat4 clip_from_world;
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) clip_from_world[c][r] = vp[static_cast<std::size_t>(4 * c + r)];
  }
  const glm::dmat4 world_from_clip = glm::inverse(clip_from_world);
  const glm::vec3 eye(scene.camera.eye[0], scene.camera.eye[1], scene.camera.eye[2]);
  const glm::vec3 target(scene.camera.target[0], scene.camera.target[1], scene.camera.target[2]);
  const bool perspective = scene.camera.fov_y_degrees > 0.0f;

  std::vector<float> out(std::size_t{width} * height * 4);
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      float* pixel = &out[(std::size_t{y} * width + x) * 4];
      std::copy(clear.begin(), clear.end(), pixel);
      const glm::dvec2 ndc(2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0);
      const glm::dvec4 near_point = world_from_clip * glm::dvec4(ndc, 0.0, 1.0);
      const glm::dvec4 far_point = world_from_clip * glm::dvec4(ndc, 1.0, 1.0);
      const glm::dvec3 a = glm::dvec3(near_point) / near_point.w, b = glm::dvec3(far_point) / far_point.w;
      if (std::abs(b.z - a.z) < 1e-15) continue;
      const double s = -a.z / (b.z - a.z);
      if (s < 0.0 || s > 1.0) continue;
      const glm::vec3 world(a + s * (b - a));
      const glm::vec2 uv(0.5f * (world.x + 1.0f), 0.5f * (1.0f - world.y));
      if (uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f) continue;

      // The plane's tangent frame is the world's: x along u, y towards row 0, z the normal.
      const glm::vec3 view = glm::normalize(perspective ? eye - world : eye - target);
      const float shift = input.parallax_scale * sampler.height_at(uv);
      const glm::vec2 shifted =
          uv + shift * glm::vec2(view.x, -view.y) / glm::vec2(static_cast<float>(tw), static_cast<float>(th));
      const glm::vec2 texel(1.0f / static_cast<float>(tw), 1.0f / static_cast<float>(th));
      const float dx = 0.5f * (sampler.height_at(shifted + glm::vec2(texel.x, 0)) -
                               sampler.height_at(shifted - glm::vec2(texel.x, 0)));
      const float dy = 0.5f * (sampler.height_at(shifted - glm::vec2(0, texel.y)) -
                               sampler.height_at(shifted + glm::vec2(0, texel.y)));
      const glm::vec3 normal = glm::normalize(glm::vec3(-dx, -dy, 1.0f));
      const Sampler::Bilinear bilinear = sampler.bilinear(shifted);
      const float tone = sampler.tone_at(bilinear);

      glm::vec3 colour(0.0f);
      for (std::size_t i = 0; i < std::min<std::size_t>(scene.lights.size(), 4); ++i) {
        const RenderLight& light = scene.lights[i];
        const glm::vec3 p(light.position[0], light.position[1], light.position[2]);
        const glm::vec3 to_light = light.point ? p - world : glm::normalize(p);
        const float falloff = light.point ? 1.0f / std::max(glm::dot(to_light, to_light), 1.0e-12f) : 1.0f;
        const glm::vec3 l = glm::normalize(to_light);
        if (l.z <= 0.0f || view.z <= 0.0f) continue;
        double lt, lp, vt, vp_angle;
        angles(l, lt, lp);
        angles(view, vt, vp_angle);
        const PairWeights w = directions.weights(lt, lp, vt, vp_angle);
        glm::vec3 btf(0.0f);
        const glm::vec3 tone_offset =
            glm::vec3(material.range.tone_chroma[0], material.range.tone_chroma[1], material.range.tone_chroma[2]) * (tone - 1.0f);
        for (int k = 0; k < 9; ++k) {
          if (w.weight[k] == 0.0f) continue;
          const std::uint32_t subspace = subspace_of(material, w.light[k], w.view[k]);
          if (input.images->images[subspace].empty()) continue;
          const float tone_weight = material.subspaces[subspace].tone_weight;
          btf += (w.weight[k] * glm::max(1.0f + tone_weight * tone_offset, glm::vec3(0.0f))) * sampler.subspace_at(bilinear, subspace);
        }
        const float relit = std::max(glm::dot(normal, l), 0.0f) / std::max(l.z, light_z_floor);
        colour += falloff * glm::vec3(light.colour[0], light.colour[1], light.colour[2]) * relit * btf;
      }
      pixel[0] = colour.r;
      pixel[1] = colour.g;
      pixel[2] = colour.b;
      pixel[3] = 1.0f;
    }
  }
  return out;
}

}  // namespace carbtf::reference
