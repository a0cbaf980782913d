// carbtf_example_host: a host engine's render loop with one carbtf material, headless. It creates its
// own Vulkan device, lets carbtf adopt it, loads the material (synthesis recorded into the host's
// command buffer), and draws the material on its own plane in its own render pass for a few frames
// while its light turns; the last frame is written as a PNG.
//
//   carbtf_example_host material.cbtf [frames] [out.png]
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "carbtf/analysis/image_io.hpp"
#include "carbtf/engine/material_file.hpp"
#include "example_host/example_host_engine.hpp"

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::printf("usage: carbtf_example_host material.cbtf [frames=8] [out=example_host.png]\n");
    return argc < 2 ? 2 : 0;
  }
  try {
    carbtf::Material material;
    if (const carbtf::Status s = carbtf::read_material_file(argv[1], material); !s.ok()) {
      std::fprintf(stderr, "carbtf_example_host: error: %s\n", s.message().c_str());
      return 1;
    }
    const int frames = argc > 2 ? std::max(1, std::atoi(argv[2])) : 8;
    const std::string out = argc > 3 ? argv[3] : "example_host.png";
    carbtf::example::ExampleHostEngine engine(640, 480, /*validation=*/false);
    engine.load_material(material, 256, 1);
    const carbtf::Mesh plane = carbtf::make_plane(4);
    std::vector<float> pixels;
    for (int frame = 0; frame < frames; ++frame) {
      const double turn = 2.0 * 3.14159265358979 * frame / frames;
      carbtf::example::HostView view;
      view.light = {static_cast<float>(0.6 * std::cos(turn)), static_cast<float>(0.6 * std::sin(turn)), 0.8f};
      pixels = engine.draw(plane, view);
      std::printf("frame %d drawn\n", frame);
    }
    std::vector<float> rgb(std::size_t{engine.width()} * engine.height() * 3);
    for (std::size_t p = 0; p < rgb.size() / 3; ++p) {
      for (int k = 0; k < 3; ++k) rgb[3 * p + k] = pixels[4 * p + k];
    }
    carbtf::write_rgb_image(out, rgb, engine.width(), engine.height(), true);
    std::printf("wrote %s\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "carbtf_example_host: error: %s\n", e.what());
    return 1;
  }
}
