#include "carbtf/engine/render/scene_pruning.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <span>
#include <utility>

#include <glm/glm.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <carbtf_gpu_shared.h>

#include "carbtf/engine/internal/direction_lookup.hpp"
#include "carbtf/engine/material/material_directions.hpp"
#include "vulkan/vk_check.hpp"

namespace carbtf {

namespace {

// One direction set of a MaterialDirections (which outlives it), with its triangles' bounding boxes.
struct DirectionSet {
  const DirectionTriangulation& triangulation;
  const DirectionLookupGrid& grid;
  std::vector<std::array<glm::vec2, 2>> boxes;  // per triangle: its bounding box (lo, hi)

  DirectionSet(const DirectionTriangulation& built, const DirectionLookupGrid& built_grid)
      : triangulation(built), grid(built_grid) {
    for (const auto& t : triangulation.triangles) {
      glm::vec2 a(1e30f), b(-1e30f);
      for (std::uint32_t k : t) {
        const glm::vec2 p(static_cast<float>(triangulation.points[k][0]),
                          static_cast<float>(triangulation.points[k][1]));
        a = glm::min(a, p);
        b = glm::max(b, p);
      }
      boxes.push_back({a, b});
    }
  }

  // Calls f(triangle) for the triangles listed in the grid cells that [lo, hi] meets (with repeats):
  // every triangle whose bounding box meets [lo, hi] is among them.
  template <typename F>
  void for_candidates(glm::vec2 lo, glm::vec2 hi, F f) const {
    const int g = static_cast<int>(grid.grid_size);
    auto cell = [g](float x) {
      return std::clamp(static_cast<int>(std::floor((x * 0.5f + 0.5f) * static_cast<float>(g))), 0, g - 1);
    };
    for (int y = cell(lo.y); y <= cell(hi.y); ++y) {
      for (int x = cell(lo.x); x <= cell(hi.x); ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * grid.grid_size + static_cast<std::size_t>(x);
        for (std::uint32_t e = grid.cell_starts[c]; e < grid.cell_starts[c + 1]; ++e) {
          if ((grid.entries[e] & gpu::CARBTF_LOOKUP_EDGE_BIT) == 0) f(grid.entries[e]);
        }
      }
    }
  }

  bool inside(glm::vec2 p) const {
    bool found = false;
    for_candidates(p, p,
                   [&](std::uint32_t t) { found = found || inside_triangle(triangulation, t, p.x, p.y); });
    return found;
  }
};

// As the fragment stage projects (carbtf_project_direction).
glm::vec2 projected(glm::vec3 d) {
  const float r = glm::length(glm::vec2(d));
  const float theta = gpu::carbtf_polar_angle(r, d.z);
  const glm::vec2 azimuth = r > 0.0f ? glm::vec2(d) / r : glm::vec2(1, 0);
  return theta / (0.5f * 3.14159265358979f) * azimuth;
}

// Measured directions that can carry weight for projected points inside [lo, hi] (widened).
void directions_in_box(const DirectionSet& set, glm::vec2 lo, glm::vec2 hi, std::set<std::uint32_t>& out) {
  const glm::vec2 widen = 0.25f * (hi - lo) + glm::vec2(1e-3f);
  lo -= widen;
  hi += widen;
  const auto& tri = set.triangulation;
  bool any = false;
  set.for_candidates(lo, hi, [&](std::uint32_t t) {
    const auto& [a, b] = set.boxes[t];
    if (a.x <= hi.x && b.x >= lo.x && a.y <= hi.y && b.y >= lo.y) {
      out.insert(tri.triangles[t].begin(), tri.triangles[t].end());
      any = true;
    }
  });
  // Where the box reaches beyond the triangulation, points take the nearest boundary point, as in the
  // fragment stage: every boundary edge that can be nearest to a point of the box counts.
  bool partly_outside = !any;
  for (const glm::vec2 corner : {lo, hi, glm::vec2(lo.x, hi.y), glm::vec2(hi.x, lo.y)}) {
    partly_outside = partly_outside || !set.inside(corner);
  }
  if (partly_outside && !tri.boundary.empty()) {
    const glm::vec2 centre = 0.5f * (lo + hi);
    const double radius = 0.5 * glm::length(hi - lo);
    double nearest = 1e30;
    for (std::uint32_t e = 0; e < tri.boundary.size(); ++e) {
      nearest = std::min(nearest, boundary_edge_distance(tri, e, centre.x, centre.y));
    }
    for (std::uint32_t e = 0; e < tri.boundary.size(); ++e) {
      if (boundary_edge_distance(tri, e, centre.x, centre.y) <= nearest + 2.0 * radius + 1e-6) {
        out.insert(tri.boundary[e].begin(), tri.boundary[e].end());
      }
    }
  }
  if (tri.points.size() == 1) out.insert(0);
}

void exact_directions(const DirectionSet& set, glm::vec2 p, std::set<std::uint32_t>& out) {
  // A tenth of the shader's threshold: a weight the fragment stage keeps is never dropped here.
  const DirectionWeights w =
      lookup_direction_weights(set.grid, set.triangulation, p.x, p.y, 0.1f * gpu::CARBTF_LOOKUP_MIN_WEIGHT);
  for (int k = 0; k < 3; ++k) {
    if (w.weight[k] != 0.0f) out.insert(w.index[k]);
  }
}

}  // namespace

struct ScenePruner::Lookups {
  Lookups(MaterialDirections built, const PruningOptions& pruning)
      : directions(std::move(built)),
        lights(directions.light_triangulation(), directions.light_grid()),
        views(directions.view_triangulation(), directions.view_grid()),
        options(pruning) {}
  MaterialDirections directions;  // before the sets, which refer to it
  DirectionSet lights, views;
  PruningOptions options;
};

Status ScenePruner::create(const Material& material, const PruningOptions& options,
                           std::unique_ptr<ScenePruner>& out) noexcept {
  try {
    std::unique_ptr<ScenePruner> pruner(new ScenePruner());
    MaterialDirections directions;
    CARBTF_TRY(MaterialDirections::build(material, directions, options.lookup_grid_size));
    pruner->lookups_ = std::make_unique<Lookups>(std::move(directions), options);
    out = std::move(pruner);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while building the scene pruner"};
  }
}

ScenePruner::~ScenePruner() = default;

Status ScenePruner::needs(const Mesh& mesh, const RenderScene& scene, std::uint32_t frame_width,
                          std::uint32_t frame_height, SceneNeeds& out) const noexcept {
  try {
    CARBTF_TRY(validate_mesh(mesh));
    if (frame_width == 0 || frame_height == 0)
      return {ErrorCode::invalid_argument, "the frame has no pixels"};
    CARBTF_TRY(check_render_lights(scene));
    const DirectionSet& lights = lookups_->lights;
    const DirectionSet& views = lookups_->views;
    const PruningOptions& options = lookups_->options;

    glm::mat4 model, clip;
    std::copy(scene.model.begin(), scene.model.end(), glm::value_ptr(model));
    const auto vp =
        view_projection(scene.camera, static_cast<float>(frame_width) / static_cast<float>(frame_height));
    std::copy(vp.begin(), vp.end(), glm::value_ptr(clip));
    const glm::vec3 eye(scene.camera.eye[0], scene.camera.eye[1], scene.camera.eye[2]);
    const glm::vec3 target(scene.camera.target[0], scene.camera.target[1], scene.camera.target[2]);
    const bool perspective = scene.camera.fov_y_degrees > 0.0f;
    const std::size_t light_count = scene.lights.size();  // checked above

    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::vector<std::pair<double, double>> densities;  // (pixels per unit of uv area, pixels) per triangle
    std::uint32_t visible = 0;
    const std::uint32_t n = std::max(options.samples_per_edge, 1u);
    // Per triangle, reused: the projected directions over it and the measured directions they reach.
    std::vector<glm::vec2> view_points;
    std::vector<std::vector<glm::vec2>> light_points(light_count);
    std::set<std::uint32_t> view_set, light_set;
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      const MeshVertex* v[3] = {&mesh.vertices[mesh.indices[i]], &mesh.vertices[mesh.indices[i + 1]],
                                &mesh.vertices[mesh.indices[i + 2]]};
      glm::vec3 world[3], normal[3];
      glm::vec4 tangent[3], clip_position[3];
      for (int k = 0; k < 3; ++k) {
        world[k] = glm::vec3(model * glm::vec4(glm::make_vec3(v[k]->position), 1.0f));
        normal[k] = glm::mat3(model) * glm::make_vec3(v[k]->normal);
        tangent[k] = glm::vec4(glm::mat3(model) * glm::make_vec3(v[k]->tangent), v[k]->tangent[3]);
        clip_position[k] = clip * glm::vec4(world[k], 1.0f);
      }
      // Outside one clip plane with all three corners: not in the frame.
      bool outside = false;
      for (int axis = 0; axis < 3 && !outside; ++axis) {
        bool below = true, above = true;
        for (const glm::vec4& c : clip_position) {
          below = below && c[axis] < (axis == 2 ? 0.0f : -c.w);
          above = above && c[axis] > c.w;
        }
        outside = below || above;
      }
      if (outside) continue;
      ++visible;

      // Texel density: screen pixels over uv area, for triangles in front of the camera.
      if (clip_position[0].w > 0 && clip_position[1].w > 0 && clip_position[2].w > 0) {
        glm::vec2 screen[3];
        for (int k = 0; k < 3; ++k) {
          screen[k] = (glm::vec2(clip_position[k]) / clip_position[k].w * 0.5f + 0.5f) *
                      glm::vec2(static_cast<float>(frame_width), static_cast<float>(frame_height));
        }
        const glm::vec2 s1 = screen[1] - screen[0], s2 = screen[2] - screen[0];
        const glm::vec2 t1(v[1]->uv[0] - v[0]->uv[0], v[1]->uv[1] - v[0]->uv[1]);
        const glm::vec2 t2(v[2]->uv[0] - v[0]->uv[0], v[2]->uv[1] - v[0]->uv[1]);
        const double pixel_area =
            0.5 * std::abs(static_cast<double>(s1.x) * s2.y - static_cast<double>(s1.y) * s2.x);
        const double uv_area =
            0.5 * std::abs(static_cast<double>(t1.x) * t2.y - static_cast<double>(t1.y) * t2.x);
        if (uv_area > 1e-14 && pixel_area > 0.0) densities.push_back({pixel_area / uv_area, pixel_area});
      }

      // Directions over the triangle, interpolated as the rasterizer does (linearly at this scale).
      view_points.clear();
      for (auto& points : light_points) points.clear();
      for (std::uint32_t a = 0; a <= n; ++a) {
        for (std::uint32_t b = 0; a + b <= n; ++b) {
          const float wa = static_cast<float>(a) / n, wb = static_cast<float>(b) / n, wc = 1.0f - wa - wb;
          const glm::vec3 p = wa * world[0] + wb * world[1] + wc * world[2];
          const glm::vec3 nn = glm::normalize(wa * normal[0] + wb * normal[1] + wc * normal[2]);
          const glm::vec3 tt =
              wa * glm::vec3(tangent[0]) + wb * glm::vec3(tangent[1]) + wc * glm::vec3(tangent[2]);
          const glm::vec3 t = glm::normalize(tt - nn * glm::dot(nn, tt));
          const float handedness = wa * tangent[0].w + wb * tangent[1].w + wc * tangent[2].w;
          const glm::vec3 up = handedness * glm::cross(nn, t);
          const glm::mat3 to_tangent = glm::transpose(glm::mat3(t, up, nn));
          const glm::vec3 view = glm::normalize(to_tangent * (perspective ? eye - p : eye - target));
          if (view.z <= 0.0f) continue;  // the fragment stage shades nothing seen from below
          view_points.push_back(projected(view));
          for (std::size_t l = 0; l < light_count; ++l) {
            const RenderLight& light = scene.lights[l];
            const glm::vec3 q(light.position[0], light.position[1], light.position[2]);
            const glm::vec3 dir = glm::normalize(to_tangent * (light.point ? q - p : q));
            if (dir.z > 0.0f) light_points[l].push_back(projected(dir));
          }
        }
      }
      if (view_points.empty()) continue;
      auto gather = [](const DirectionSet& set, const std::vector<glm::vec2>& points,
                       std::set<std::uint32_t>& found) {
        glm::vec2 lo(1e30f), hi(-1e30f);
        for (const glm::vec2& p : points) {
          lo = glm::min(lo, p);
          hi = glm::max(hi, p);
        }
        if (glm::length(hi - lo) < 1e-6f) {
          exact_directions(set, points.front(), found);
        } else {
          directions_in_box(set, lo, hi, found);
        }
      };
      view_set.clear();
      gather(views, view_points, view_set);
      for (std::size_t l = 0; l < light_count; ++l) {
        if (light_points[l].empty()) continue;
        light_set.clear();
        gather(lights, light_points[l], light_set);
        for (std::uint32_t a : light_set) {
          for (std::uint32_t b : view_set) pairs.insert({a, b});
        }
      }
    }

    SceneNeeds needs;
    needs.pairs.assign(pairs.begin(), pairs.end());
    needs.subspaces = lookups_->directions.subspaces_of(needs.pairs);
    needs.visible_triangles = visible;
    needs.periodic = mesh.periodic_uv;
    // The density that 90% of the covered pixels need at most: a mesh's uv-degenerate corners (a sphere's
    // poles) would otherwise ask for the largest size the options allow.
    std::sort(densities.begin(), densities.end());
    double total = 0.0, density = 1.0;
    for (const auto& d : densities) total += d.second;
    for (double covered = 0.0; const auto& d : densities) {
      covered += d.second;
      density = d.first;
      if (covered >= 0.9 * total) break;
    }
    const double texels = std::sqrt(std::max(density, 1.0));
    std::uint32_t size = std::max(options.min_texture_size, 1u);
    while (size < texels && size < options.max_texture_size) size *= 2;
    needs.texture_size = std::min(size, std::max(options.max_texture_size, options.min_texture_size));
    out = std::move(needs);
    return {};
  } catch (const std::bad_alloc&) {
    return {ErrorCode::out_of_host_memory, "out of host memory while working out what the scene needs"};
  }
}

}  // namespace carbtf
