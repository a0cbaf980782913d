#include "carbtf/reference/render_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/glm.hpp>

#include "carbtf/engine/material/material_directions.hpp"
#include "carbtf/engine/material/mip_levels.hpp"
#include "carbtf/engine/render/material_tables.hpp"
#include "carbtf/engine/render/relief_horizons.hpp"
#include "carbtf/engine/render/relief_normals.hpp"
#include "carbtf/engine/render/rendered_values.hpp"
#include "carbtf/reference/parallax_march.hpp"

namespace carbtf::reference {

namespace {

// One texture's mip chain: level 0 as given, each level above the mean of 2 x 2 texels below it, in the
// order of operations of a blit's linear filter at the half-texel point (mix along x, then along y).
struct MipChain {
  std::vector<std::vector<float>> levels;  // levels[0] is a copy of level 0
  std::uint32_t channels = 1;

  MipChain(std::span<const float> level0, std::uint32_t width, std::uint32_t height, std::uint32_t channels_,
           std::uint32_t count)
      : channels(channels_) {
    levels.emplace_back(level0.begin(), level0.end());
    for (std::uint32_t l = 1; l < count; ++l)
      levels.push_back(next_mip_level(levels.back(), width >> (l - 1), height >> (l - 1), channels));
  }
};

// The range texture's layer 1 with its levels: the relief normal and, in w, its own length at every
// level (the binding's set_range_layer()).
MipChain relief_chain(std::span<const float> level0, std::uint32_t width, std::uint32_t height,
                      std::uint32_t count) {
  MipChain chain(level0, width, height, 4, count);
  for (std::vector<float>& level : chain.levels) store_normal_lengths(level);
  return chain;
}

// The range texture's layers 2 and 3 (relief_horizons.hpp's horizon_layer()).
std::vector<float> horizon_texels(std::span<const float> horizons, std::size_t texels, std::uint32_t half) {
  std::vector<float> out;
  horizon_layer(horizons, texels, half, out);
  return out;
}

// A level of detail split as the shader's carbtf_split_lod().
struct Lod {
  int level;
  float t;
  explicit Lod(float lod) : level(static_cast<int>(std::floor(lod))), t(lod - static_cast<float>(level)) {}
};

struct Sampler {
  const ReferenceRenderInput& input;
  std::uint32_t width, height;
  float range_mean;
  MipChain range, relief;           // heights and tone; normal (relief_normals.hpp)
  MipChain horizons_a, horizons_b;  // horizons of azimuths 0-3 and 4-7 (relief_horizons.hpp)
  std::vector<MipChain> images;     // per subspace, empty levels where it was not synthesized

  struct Bilinear {
    int x0, y0, x1, y1;
    float fx, fy;
  };
  Bilinear bilinear(glm::vec2 uv, int level) const {
    const glm::vec2 u = input.wrap ? uv - glm::floor(uv) : uv;
    const int w = static_cast<int>(width >> level), h = static_cast<int>(height >> level);
    const glm::vec2 t = u * glm::vec2(static_cast<float>(w), static_cast<float>(h)) - 0.5f;
    const glm::vec2 base = glm::floor(t);
    const int ix = static_cast<int>(std::clamp(base.x, -1.0f, static_cast<float>(w)));
    const int iy = static_cast<int>(std::clamp(base.y, -1.0f, static_cast<float>(h)));
    if (input.wrap) {
      return {ix < 0 ? w - 1 : ix,      iy < 0 ? h - 1 : iy, ix + 1 >= w ? 0 : ix + 1,
              iy + 1 >= h ? 0 : iy + 1, t.x - base.x,        t.y - base.y};
    }
    return {std::clamp(ix, 0, w - 1),
            std::clamp(iy, 0, h - 1),
            std::clamp(ix + 1, 0, w - 1),
            std::clamp(iy + 1, 0, h - 1),
            t.x - base.x,
            t.y - base.y};
  }
  // Channel c of `chain` at uv, bilinear within a level, trilinear between two (the shader's order).
  glm::vec4 filtered(const MipChain& chain, glm::vec2 uv, float lod) const {
    auto at_level = [&](int level) {
      const Bilinear b = bilinear(uv, level);
      const std::vector<float>& map = chain.levels[static_cast<std::size_t>(level)];
      const std::size_t w = width >> level;
      auto at = [&](int x, int y) {
        glm::vec4 v(0.0f);
        const std::size_t base = (static_cast<std::size_t>(y) * w + x) * chain.channels;
        for (std::uint32_t k = 0; k < std::min(chain.channels, 4u); ++k)
          v[static_cast<int>(k)] = map[base + k];
        return v;
      };
      const glm::vec4 top = glm::mix(at(b.x0, b.y0), at(b.x1, b.y0), b.fx);
      const glm::vec4 bottom = glm::mix(at(b.x0, b.y1), at(b.x1, b.y1), b.fx);
      return glm::mix(top, bottom, b.fy);
    };
    const Lod s(lod);
    glm::vec4 value = at_level(s.level);
    if (s.t > 0.0f) value = glm::mix(value, at_level(s.level + 1), s.t);
    return value;
  }
  float height_at(glm::vec2 uv, float lod) const { return filtered(range, uv, lod).x - range_mean; }
  glm::vec3 tone_at(glm::vec2 uv, float lod) const {
    const glm::vec4 texel = filtered(range, uv, lod);
    return {texel.y, texel.z, texel.w};
  }
  // The shader's carbtf_relief(): the trilinear blend of the normals scaled to the blend of their lengths.
  glm::vec4 relief_at(glm::vec2 uv, float lod) const {
    const glm::vec4 value = filtered(relief, uv, lod);
    return glm::vec4(glm::vec3(value) * (value.w / glm::length(glm::vec3(value))), value.w);
  }
  glm::vec3 subspace_at(glm::vec2 uv, float lod, std::uint32_t subspace) const {
    return glm::vec3(filtered(images[subspace], uv, lod));
  }
};

// The relief at a point, as the shader's CarbtfRelief holds it.
struct ReliefPoint {
  glm::vec3 normal;
  float normal_length;
  glm::vec3 tone;
  std::array<float, kReliefHorizonDirections> horizons{};
};

ReliefPoint relief_point(const Sampler& sampler, glm::vec2 uv, float lod, bool shadows) {
  const glm::vec4 relief = sampler.relief_at(uv, lod);
  ReliefPoint point{glm::vec3(relief), relief.w, sampler.tone_at(uv, lod), {}};
  if (shadows) {
    const glm::vec4 a = sampler.filtered(sampler.horizons_a, uv, lod),
                    b = sampler.filtered(sampler.horizons_b, uv, lod);
    point.horizons = {a.x, a.y, a.z, a.w, b.x, b.y, b.z, b.w};
  }
  return point;
}

// The shader's carbtf_relief_lit(): the relit factor and the specular lobe of a relief point, the lobe of
// strength `lobe_strength` (the material's at this view).
struct ReliefLight {
  float relit;
  float lobe;
};

ReliefLight relief_light(const Material& material, const ReliefPoint& point, glm::vec3 l,
                         glm::vec3 half_vector, float lobe_strength, float light_z_floor, bool shadows) {
  const float n_dot_l = std::max(glm::dot(point.normal, l), 0.0f);
  const float visibility = shadows ? relief_visibility(point.horizons, {l.x, l.y, l.z}) : 1.0f;
  ReliefLight lit{
      kReliefAmbient + (1.0f - kReliefAmbient) * n_dot_l / std::max(l.z, light_z_floor) * visibility, 0.0f};
  if (lobe_strength > 0.0f) {
    const float n_dot_h = std::max(glm::dot(point.normal, half_vector), 0.0f) / point.normal_length;
    lit.lobe = lobe_strength * n_dot_l * visibility * std::pow(n_dot_h, material.range.specular_gloss);
  }
  return lit;
}

// relief_chroma_mix() of glm colours.
glm::vec3 chroma_from(glm::vec3 colour, glm::vec3 chroma_colour) {
  const std::array<float, 3> mixed =
      relief_chroma_mix({colour.r, colour.g, colour.b}, {chroma_colour.r, chroma_colour.g, chroma_colour.b});
  return {mixed[0], mixed[1], mixed[2]};
}

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
  if (!input.tone_map.empty() && input.tone_map.size() != 3 * input.range_map.size()) {
    throw std::invalid_argument("render_plane: the relief tone is not the range map's size");
  }
  if (const Status s = check_render_lights(scene); !s.ok())
    throw std::invalid_argument("render_plane: " + s.message());
  MaterialDirections directions;
  if (const Status s = MaterialDirections::build(material, directions); !s.ok()) {
    throw std::invalid_argument("render_plane: the material's directions: " + s.message());
  }
  const float light_z_floor = relight_floor(material);
  // The mean and the march's bounds as the binding computes them.
  const ReliefExtent extent = relief_extent(input.range_map, input.parallax_scale);
  const std::uint32_t levels = std::clamp(input.mip_levels, 1u, mip_level_count(tw, th));
  const std::uint32_t relief_levels =
      std::clamp(input.relief_levels > 0 ? input.relief_levels : levels + material.range.chroma_levels, 1u,
                 mip_level_count(tw, th));
  const float chroma_top_level = static_cast<float>(relief_levels - 1);
  const bool shadows = material.range.shadow_scale > 0.0f;
  std::vector<float> horizons;
  if (shadows) relief_horizons(input.range_map, tw, th, input.wrap, material.range.shadow_scale, horizons);
  Sampler sampler{input,
                  tw,
                  th,
                  extent.mean,
                  MipChain(height_tone_texels(input.range_map, input.tone_map), tw, th, 4, relief_levels),
                  relief_chain(normal_texels(input.range_map, tw, th, input.wrap), tw, th, relief_levels),
                  MipChain(horizon_texels(horizons, input.range_map.size(), 0), tw, th, 4, relief_levels),
                  MipChain(horizon_texels(horizons, input.range_map.size(), 1), tw, th, 4, relief_levels),
                  {}};
  for (std::size_t i = 0; i < input.images->images.size(); ++i) {
    const auto& image = input.images->images[i];
    sampler.images.emplace_back(image, tw, th, input.images->channels[i], image.empty() ? 0 : levels);
  }

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

  // Where pixel (x, y)'s centre ray meets the plane (z = 0), in world units; false when it does not.
  auto hit = [&](std::uint32_t x, std::uint32_t y, glm::dvec3& world) {
    const glm::dvec2 ndc(2.0 * (x + 0.5) / width - 1.0, 2.0 * (y + 0.5) / height - 1.0);
    const glm::dvec4 near_point = world_from_clip * glm::dvec4(ndc, 0.0, 1.0);
    const glm::dvec4 far_point = world_from_clip * glm::dvec4(ndc, 1.0, 1.0);
    const glm::dvec3 a = glm::dvec3(near_point) / near_point.w, b = glm::dvec3(far_point) / far_point.w;
    if (std::abs(b.z - a.z) < 1e-15) return false;
    const double s = -a.z / (b.z - a.z);
    world = a + s * (b - a);
    return s >= 0.0 && s <= 1.0;
  };
  auto uv_of = [](const glm::dvec3& world) {
    return glm::dvec2(0.5 * (world.x + 1.0), 0.5 * (1.0 - world.y));
  };
  // The fragment stage's carbtf_material_lod(): fine derivatives are differences within the pixel's
  // 2 x 2 quad, the same for both pixels of its row (x) or column (y).
  const float top_level = static_cast<float>(levels - 1);
  auto lod_at = [&](std::uint32_t x, std::uint32_t y) {
    if (levels == 1) return 0.0f;
    glm::dvec3 w0, w1, w2, w3;
    hit(x & ~1u, y, w0);
    hit(x | 1u, y, w1);
    hit(x, y & ~1u, w2);
    hit(x, y | 1u, w3);
    const glm::dvec2 size(static_cast<double>(tw), static_cast<double>(th));
    const glm::dvec2 dx = (uv_of(w1) - uv_of(w0)) * size, dy = (uv_of(w3) - uv_of(w2)) * size;
    const double footprint = std::max(glm::dot(dx, dx), glm::dot(dy, dy));
    return footprint > 1.0 ? std::min(static_cast<float>(0.5 * std::log2(footprint)), top_level) : 0.0f;
  };

  std::vector<float> out(std::size_t{width} * height * 4);
  for (std::uint32_t y = 0; y < height; ++y) {
    for (std::uint32_t x = 0; x < width; ++x) {
      float* pixel = &out[(std::size_t{y} * width + x) * 4];
      std::copy(clear.begin(), clear.end(), pixel);
      glm::dvec3 world_point;
      if (!hit(x, y, world_point)) continue;
      const glm::vec3 world(world_point);
      const glm::vec2 uv(0.5f * (world.x + 1.0f), 0.5f * (1.0f - world.y));
      if (uv.x < 0.0f || uv.x > 1.0f || uv.y < 0.0f || uv.y > 1.0f) continue;
      const float lod = lod_at(x, y);

      // The plane's tangent frame is the world's: x along u, y towards row 0, z the normal.
      const glm::vec3 view = glm::normalize(perspective ? eye - world : eye - target);
      const glm::vec2 shifted =
          parallax_march([&](glm::vec2 at) { return sampler.height_at(at, lod); }, uv, view,
                         glm::vec2(static_cast<float>(tw), static_cast<float>(th)), input.parallax_scale,
                         extent, input.parallax_steps);
      // The relief at the fragment's level and RangeTiles::chroma_levels above, whose chroma the colour
      // takes (carbtf_material_shade()).
      const float chroma_lod =
          std::min(lod + static_cast<float>(material.range.chroma_levels), chroma_top_level);
      ReliefPoint fine = relief_point(sampler, shifted, lod, shadows);
      if (input.normals_from_heights) {
        const glm::vec2 texel(1.0f / static_cast<float>(tw), 1.0f / static_cast<float>(th));
        const float dx = 0.5f * (sampler.height_at(shifted + glm::vec2(texel.x, 0), 0.0f) -
                                 sampler.height_at(shifted - glm::vec2(texel.x, 0), 0.0f));
        const float dy = 0.5f * (sampler.height_at(shifted - glm::vec2(0, texel.y), 0.0f) -
                                 sampler.height_at(shifted + glm::vec2(0, texel.y), 0.0f));
        fine.normal = glm::normalize(glm::vec3(-dx, -dy, 1.0f));
      }
      const ReliefPoint coarse = relief_point(sampler, shifted, chroma_lod, shadows);
      const glm::vec3 tone_offset = fine.tone - 1.0f;
      const glm::vec3 chroma_tone_offset =
          (tone_planes(material.range) == 1 ? coarse.tone : fine.tone) - 1.0f;

      glm::vec3 colour(0.0f);
      for (std::size_t i = 0; i < scene.lights.size(); ++i) {  // at most kMaxRenderLights: checked on entry
        const RenderLight& light = scene.lights[i];
        const glm::vec3 p(light.position[0], light.position[1], light.position[2]);
        const glm::vec3 to_light = light.point ? p - world : glm::normalize(p);
        const float falloff = light.point ? 1.0f / std::max(glm::dot(to_light, to_light), 1.0e-12f) : 1.0f;
        const glm::vec3 l = glm::normalize(to_light);
        if (l.z <= 0.0f || view.z <= 0.0f) continue;
        double lt, lp, vt, vp_angle;
        angles(l, lt, lp);
        angles(view, vt, vp_angle);
        const PairWeights w = directions.weights(lt, lp, vt, vp_angle, input.pair_coupling);
        glm::vec3 btf(0.0f), chroma_btf(0.0f);
        for (int k = 0; k < 9; ++k) {
          if (w.weight[k] == 0.0f) continue;
          const std::uint32_t subspace = subspace_of(material, w.light[k], w.view[k]);
          if (input.images->images[subspace].empty()) continue;
          const float tone_weight = rendered_tone_weight(material.subspaces[subspace].tone_weight);
          const std::array<float, 3> gain = rendered_pair_gain(material, w.light[k], w.view[k]);
          const glm::vec3 part = w.weight[k] * (glm::vec3(gain[0], gain[1], gain[2]) *
                                                sampler.subspace_at(shifted, lod, subspace));
          btf += glm::max(1.0f + tone_weight * tone_offset, glm::vec3(0.0f)) * part;
          chroma_btf += glm::max(1.0f + tone_weight * chroma_tone_offset, glm::vec3(0.0f)) * part;
        }
        const glm::vec3 half_vector = glm::normalize(l + view);
        const float lobe_strength =
            material.range.specular_strength * specular_view_gain(material.range.specular_view_power, view.z);
        const ReliefLight lit =
            relief_light(material, fine, l, half_vector, lobe_strength, light_z_floor, shadows);
        const ReliefLight chroma_lit =
            relief_light(material, coarse, l, half_vector, lobe_strength, light_z_floor, shadows);
        const glm::vec3 shade =
            chroma_from(lit.relit * btf + lit.lobe, chroma_lit.relit * chroma_btf + chroma_lit.lobe);
        colour += falloff * glm::vec3(light.colour[0], light.colour[1], light.colour[2]) * shade;
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
