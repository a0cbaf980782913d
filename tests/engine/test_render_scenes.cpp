// Render scenes beyond one plane: pruning a scene to the subspace images it needs, the light limit of a
// draw, and subspace images made resident frame by frame; each renders the pixels of the plain path.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "carbtf/engine/internal/direction_lookup.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "carbtf/engine/render/material_binding.hpp"
#include "carbtf/engine/render/material_tables.hpp"
#include "carbtf/engine/render/mesh_renderer.hpp"
#include "carbtf/engine/render/resident_images.hpp"
#include "carbtf/engine/render/scene_pruning.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/render_reference.hpp"
#include "carbtf/reference/synthetic_material.hpp"
#include "rendered_floats.hpp"
#include "test_materials.hpp"
#include "test_support.hpp"

using namespace carbtf;

namespace {

// The UBO2003 81 x 81 direction sets with 20 subspace images laid out by elevation, as segmentation
// tends to: light ring (0..5) and view ring, 3 * light ring + view ring / 2, and 18, 19 for the
// grazing light ring's azimuths past 180 degrees.
Material ubo_material() {
  Material m = test::bumpy_material();
  const Material twenty = synthetic_material(20, 2);
  m.subspaces = twenty.subspaces;
  m.lights = m.views = test::ubo2003_material_directions();
  m.subspace_index.clear();
  auto ring = [](const MaterialDirection& d) {
    return static_cast<std::uint32_t>(std::lround(d.theta / 0.2617994f));
  };
  for (std::uint32_t l = 0; l < 81; ++l) {
    for (std::uint32_t v = 0; v < 81; ++v) {
      std::uint32_t s = 3 * ring(m.lights[l]) + ring(m.views[v]) / 2;
      if (ring(m.lights[l]) == 5 && m.lights[l].phi > 3.2f) s = 18 + ring(m.views[v]) % 2;
      m.subspace_index.push_back(static_cast<std::uint8_t>(s));
    }
  }
  return m;
}

// The 64^2 block, seed 3, that these renders synthesize, of `subspaces` (empty: all).
SynthesisRequest render_request(const std::vector<std::uint32_t>& subspaces) {
  SynthesisRequest request;
  request.seed = 3;
  request.width = request.height = 64;
  request.margin = 8;
  request.subspaces = subspaces;
  request.mip_levels = 0;  // as ResidentImages makes them
  return request;
}

// `mesh` under `scene` through `binding`, 96^2 RGBA32F.
std::vector<float> draw(Context& context, const MaterialBinding& binding, const Mesh& mesh,
                        const RenderScene& scene) {
  RenderTargetInfo target;
  target.width = target.height = 96;
  target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  std::unique_ptr<MeshRenderer> renderer;
  REQUIRE(MeshRenderer::create(context, binding, target, renderer).ok());
  REQUIRE(renderer->set_mesh(mesh).ok());
  RenderedImage frame;
  const Status status = renderer->render(scene, frame);
  INFO(status.message());
  REQUIRE(status.ok());
  return test::as_floats(frame);
}

std::vector<float> render_with(Context& context, const Material& m,
                               const std::vector<std::uint32_t>& subspaces, const Mesh& mesh,
                               const RenderScene& scene) {
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  REQUIRE(SubspaceSynthesizer::create(context, synthesizer).ok());
  REQUIRE(synthesizer->prepare(m, render_request(subspaces)).ok());
  REQUIRE(context.submit_and_wait([&](VkCommandBuffer cb) { return synthesizer->record(cb); }).ok());
  MaterialBindingInfo info;
  info.seed = 3;
  std::unique_ptr<MaterialBinding> binding;
  REQUIRE(MaterialBinding::create(context, m, material_textures(*synthesizer, m), info, binding).ok());
  REQUIRE(binding->upload_and_wait().ok());
  return draw(context, *binding, mesh, scene);
}

}  // namespace

TEST_CASE("scene pruning: a scene seen from above needs fewer subspace images and renders the same pixels",
          "[render][gpu]") {
  test::ValidatedContext context;
  const Material m = ubo_material();
  RenderScene scene;
  Mesh mesh;
  bool expect_fewer = false;
  SECTION("a plane from above, perspective, one directional light") {
    mesh = make_plane(4);
    scene.camera.eye = {0.1f, 0.2f, 2.8f};
    scene.camera.up = {0, 1, 0};
    // Towards the light at theta 45, phi 60 degrees.
    const float s45 = std::sqrt(0.5f);
    scene.lights = {{false, {s45 * 0.5f, s45 * std::sqrt(0.75f), s45}, {1, 1, 1}}};
    expect_fewer = true;
  }
  SECTION("a sphere from the side, a point light and a grazing light") {
    mesh = make_sphere(24, 12);
    scene.camera.eye = {2.4f, 1.5f, 1.2f};
    scene.lights = {{true, {1.5f, -1.0f, 1.6f}, {2, 2, 2}}, {false, {0.2f, 1.0f, 0.05f}, {0.5f, 0.5f, 0.5f}}};
  }
  std::unique_ptr<ScenePruner> pruner;
  REQUIRE(ScenePruner::create(m, {}, pruner).ok());
  SceneNeeds needs;
  const Status status = pruner->needs(mesh, scene, 96, 96, needs);
  INFO(status.message());
  REQUIRE(status.ok());
  INFO("needs " << needs.subspaces.size() << " of 20 subspace images, " << needs.pairs.size()
                << " pairs, texture " << needs.texture_size);
  REQUIRE(!needs.subspaces.empty());
  if (expect_fewer) CHECK(needs.subspaces.size() <= 3);
  CHECK(needs.texture_size >= 32);

  const std::vector<float> full = render_with(*context, m, {}, mesh, scene);
  const std::vector<float> pruned = render_with(*context, m, needs.subspaces, mesh, scene);
  std::size_t covered = 0;
  for (std::size_t i = 3; i < full.size(); i += 4) covered += full[i] == 1.0f;
  CHECK(covered > full.size() / 4 / 8);
  test::require_bitwise_equal(pruned, full, 96 * 4);
  context.require_clean();
}

TEST_CASE("a scene with more lights than a draw shades with is refused, not cut", "[render][gpu]") {
  test::ValidatedContext context;
  const Material m = ubo_material();
  const Mesh mesh = make_plane(4);
  RenderScene scene;
  scene.camera.eye = {0.1f, 0.2f, 2.8f};
  scene.camera.up = {0, 1, 0};
  scene.lights.assign(kMaxRenderLights + 1, RenderLight{});
  std::unique_ptr<ScenePruner> pruner;
  REQUIRE(ScenePruner::create(m, {}, pruner).ok());
  SceneNeeds needs;
  const Status pruned = pruner->needs(mesh, scene, 96, 96, needs);
  CHECK(pruned.code() == ErrorCode::invalid_argument);
  CHECK_THAT(pruned.message(), Catch::Contains("5 lights") && Catch::Contains("at most 4"));

  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  REQUIRE(SubspaceSynthesizer::create(*context, synthesizer).ok());
  REQUIRE(synthesizer->prepare(m, render_request({})).ok());
  REQUIRE(context->submit_and_wait([&](VkCommandBuffer cb) { return synthesizer->record(cb); }).ok());
  std::unique_ptr<MaterialBinding> binding;
  REQUIRE(MaterialBinding::create(*context, m, material_textures(*synthesizer, m), MaterialBindingInfo{3},
                                  binding)
              .ok());
  REQUIRE(binding->upload_and_wait().ok());
  RenderTargetInfo target;
  target.width = target.height = 32;
  std::unique_ptr<MeshRenderer> renderer;
  REQUIRE(MeshRenderer::create(*context, *binding, target, renderer).ok());
  REQUIRE(renderer->set_mesh(mesh).ok());
  RenderedImage frame;
  const Status drawn = renderer->render(scene, frame);
  CHECK(drawn.code() == ErrorCode::invalid_argument);
  CHECK_THAT(drawn.message(), Catch::Contains("kMaxRenderLights"));
  scene.lights.resize(kMaxRenderLights);  // at the limit: drawn
  CHECK(renderer->render(scene, frame).ok());
  context.require_clean();
}

TEST_CASE("subspace images made resident frame by frame render the pixels of one synthesis of them all",
          "[render][gpu]") {
  test::ValidatedContext context;
  const Material m = ubo_material();
  const Mesh mesh = make_sphere(24, 12);
  RenderScene scene;
  scene.camera.eye = {2.4f, 1.5f, 1.2f};
  scene.lights = {{true, {1.5f, -1.0f, 1.6f}, {2, 2, 2}}, {false, {0.2f, 1.0f, 0.05f}, {0.5f, 0.5f, 0.5f}}};
  std::unique_ptr<ScenePruner> pruner;
  REQUIRE(ScenePruner::create(m, {}, pruner).ok());
  SceneNeeds needs;
  REQUIRE(pruner->needs(mesh, scene, 96, 96, needs).ok());
  REQUIRE(needs.subspaces.size() >= 2);
  const std::vector<float> at_once = render_with(*context, m, needs.subspaces, mesh, scene);

  std::unique_ptr<ResidentImages> resident;
  REQUIRE(ResidentImages::create(*context, m, 64, 0, resident).ok());
  MaterialBindingInfo info;
  info.seed = 3;
  std::unique_ptr<MaterialBinding> binding;
  REQUIRE(MaterialBinding::create(*context, m, resident->textures(), info, binding).ok());
  REQUIRE(context
              ->submit_and_wait([&](VkCommandBuffer cb) {
                resident->record_transition(cb);
                return binding->record_upload(cb);
              })
              .ok());
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  REQUIRE(SubspaceSynthesizer::create(*context, synthesizer).ok());
  // Two frames: the first needs half the images, the second all of them and gets only the rest.
  const std::size_t half = needs.subspaces.size() / 2;
  const std::vector<std::uint32_t> first(needs.subspaces.begin(), needs.subspaces.begin() + half);
  for (const std::vector<std::uint32_t>& frame_needs : {first, needs.subspaces}) {
    const std::vector<std::uint32_t> added = resident->missing(frame_needs);
    CHECK(added.size() == (frame_needs.size() == half ? half : needs.subspaces.size() - half));
    REQUIRE(synthesizer->prepare(m, render_request(added)).ok());
    REQUIRE(context
                ->submit_and_wait([&](VkCommandBuffer cb) {
                  if (Status status = synthesizer->record(cb); !status.ok()) return status;
                  return resident->record_add(cb, *synthesizer, added);
                })
                .ok());
    REQUIRE(binding->set_layers(m, resident->layers()).ok());
  }
  CHECK(resident->missing(needs.subspaces).empty());
  CHECK(resident->resident_count() == needs.subspaces.size());

  test::require_bitwise_equal(draw(*context, *binding, mesh, scene), at_once, 96 * 4);

  // What cannot be right is refused: another material's layer count, an image the synthesis lacks.
  CHECK(binding->set_layers(m, std::vector<std::uint32_t>(3, 0)).code() == ErrorCode::invalid_argument);
  // A layer the pair table's 16 bits cannot hold (MaterialTablesHeader::pair_table).
  std::vector<std::uint32_t> too_far = resident->layers();
  too_far.back() = 65535u;
  const Status too_far_status = binding->set_layers(m, too_far);
  CHECK(too_far_status.code() == ErrorCode::invalid_argument);
  CHECK_THAT(too_far_status.message(), Catch::Contains("65535"));
  const std::uint32_t absent = needs.subspaces.front();
  REQUIRE(synthesizer->prepare(m, render_request({absent == 0 ? 1u : 0u})).ok());
  const std::vector<std::uint32_t> lacking{absent};
  const Status refused = context->submit_and_wait(
      [&](VkCommandBuffer cb) { return resident->record_add(cb, *synthesizer, lacking); });
  CHECK(refused.code() == ErrorCode::invalid_argument);
  context.require_clean();
}
