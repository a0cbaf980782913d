// Embedding as a host engine does it (host/example_host): the host creates its device, carbtf adopts
// it, synthesizes into the host's command buffer and hands over a descriptor set; the host draws the
// material in its own render pass with its own pipeline and shaders. Its picture must equal carbtf's
// own render pass on the same scene, validation must stay silent, and the host's device must outlive
// carbtf.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "carbtf/engine/render/mesh_renderer.hpp"
#include "example_host/example_host_engine.hpp"
#include "test_materials.hpp"

using namespace carbtf;

TEST_CASE("a host engine draws carbtf's material in its own pass on its own adopted device",
          "[embedding][gpu]") {
  const Material m = test::bumpy_material();
  example::ExampleHostEngine host(96, 72, /*validation=*/true);
  host.load_material(m, 64, 3);
  REQUIRE(host.carbtf_context() != nullptr);
  CHECK_FALSE(host.carbtf_context()->owns_device());
  CHECK(host.carbtf_context()->device() == host.adopt_info().device);

  example::HostView view;
  view.eye = {0.3f, -1.7f, 2.0f};
  view.light = {0.4f, 0.3f, 0.85f};
  const Mesh plane = make_plane(4);
  const std::vector<float> hosted = host.draw(plane, view);

  // The same scene through carbtf's own render pass on the adopted context and the host's binding.
  RenderTargetInfo target;
  target.width = 96;
  target.height = 72;
  target.colour_format = VK_FORMAT_R32G32B32A32_SFLOAT;
  target.clear = {0, 0, 0, 0};
  std::unique_ptr<MeshRenderer> renderer;
  REQUIRE(MeshRenderer::create(*host.carbtf_context(), *host.binding(), target, renderer).ok());
  REQUIRE(renderer->set_mesh(plane).ok());
  RenderScene scene;
  scene.camera.eye = view.eye;
  scene.lights = {{false, view.light, {1, 1, 1}}};
  RenderedImage own;
  const Status status = renderer->render(scene, own);
  INFO(status.message());
  REQUIRE(status.ok());
  std::vector<float> expected(own.bytes.size() / 4);
  std::memcpy(expected.data(), own.bytes.data(), own.bytes.size());
  renderer.reset();

  REQUIRE(expected.size() == hosted.size());
  double peak = 0.0, worst = 0.0;
  std::size_t covered = 0;
  for (std::size_t i = 0; i < hosted.size(); i += 4) {
    CHECK(hosted[i + 3] == expected[i + 3]);  // the same coverage
    if (expected[i + 3] != 1.0f) continue;
    ++covered;
    for (int k = 0; k < 3; ++k) {
      peak = std::max(peak, static_cast<double>(expected[i + k]));
      worst = std::max(worst, std::abs(static_cast<double>(hosted[i + k]) - expected[i + k]));
    }
  }
  INFO(covered << " pixels, peak " << peak << ", worst difference " << worst);
  CHECK(covered > 96u * 72u / 4u);
  CHECK(peak > 0.0);
  // Both pipelines run carbtf_material.glsl; only the host's own tangent-frame and camera code differ.
  CHECK(worst <= 1e-5 * peak);

  host.unload_material();
  CHECK(host.device_alive());  // carbtf destroyed nothing of the host's
  std::string all;
  for (const std::string& message : host.messages()) all += message + "\n";
  INFO("validation messages:\n" << all);
  CHECK(host.messages().empty());
}
