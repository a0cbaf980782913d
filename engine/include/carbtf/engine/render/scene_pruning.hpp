// Only what a scene needs (docs/design.md 4.7): before synthesis, which subspace images and what texture
// resolution one frame of a mesh under a camera and lights can use.
//
// Per triangle of the mesh that is not outside the view frustum: the light and view directions in the
// triangle's tangent frame are evaluated on a grid of points over the triangle, as the rasterizer
// interpolates them. When they do not vary over the triangle, the direction weights there (from the
// same lookup grids the fragment stage uses) name the measured directions exactly; when they do, every
// measured direction of a direction-set triangle meeting their projected bounding box, widened by a
// quarter of its size, counts. Occlusion is ignored. So the set errs on the large side: a frame
// rendered from only these subspace images equals the one rendered from all of them (the tests check
// this bit for bit).
// The texture size is the power of two that gives at least one texel per pixel to the triangles
// covering 90% of the frame's mesh pixels (by their pixel-to-uv area ratio; the most magnified tenth,
// such as a sphere's uv-degenerate poles, does not decide), clamped to the options' range.
// Thread safety: a pruner is immutable after create(); needs() may run on any thread.
#pragma once

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/render/mesh.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"

namespace carbtf {

struct PruningOptions {
  std::uint32_t samples_per_edge = 4;  // the grid over each triangle: (n + 1)(n + 2) / 2 points
  std::uint32_t min_texture_size = 32;
  std::uint32_t max_texture_size = 4096;
  std::uint32_t lookup_grid_size = 64;  // as MaterialBindingInfo::lookup_grid_size
};

struct SceneNeeds {
  std::vector<std::uint32_t> subspaces;  // ascending
  // The distinct measured (light, view) pairs that can carry weight, ascending.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::uint32_t texture_size = 0;
  std::uint32_t visible_triangles = 0;
  // The mesh's texture coordinates wrap (Mesh::periodic_uv): synthesize periodic images.
  bool periodic = false;
};

// Built once per material (its direction lookups), then asked once per frame.
class ScenePruner {
 public:
  // invalid_argument when the material's directions cannot be triangulated.
  static Status create(const Material& material, const PruningOptions& options,
                       std::unique_ptr<ScenePruner>& out) noexcept;
  ~ScenePruner();

  Status needs(const Mesh& mesh, const RenderScene& scene, std::uint32_t frame_width,
               std::uint32_t frame_height, SceneNeeds& out) const noexcept;

 private:
  ScenePruner() = default;
  struct Lookups;
  std::unique_ptr<Lookups> lookups_;
};

}  // namespace carbtf
