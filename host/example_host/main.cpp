// carbtf_example_host: a host engine's render loop with one carbtf material, headless. It creates its
// own Vulkan device, lets carbtf adopt it, loads the material (synthesis recorded into the host's
// command buffer), and draws the material on its own plane in its own render pass for a few frames
// while its light turns; the last frame is written as a binary PPM. It links carbtf's engine only (no
// analysis library, no image library), as a host engine would.
//
//   carbtf_example_host material.cbtf [frames] [out.ppm]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "carbtf/engine/material/material_file.hpp"
#include "example_host/example_host_engine.hpp"

namespace {

// Linear RGBA pixels (the host's float target, row 0 at the top) as an 8-bit sRGB binary PPM.
bool write_ppm(const std::string& path, const std::vector<float>& rgba, std::uint32_t width,
               std::uint32_t height) {
  std::ofstream file(path, std::ios::binary);
  file << "P6\n" << width << " " << height << "\n255\n";
  std::vector<unsigned char> bytes(std::size_t{width} * height * 3);
  for (std::size_t p = 0; p < bytes.size() / 3; ++p) {
    for (int k = 0; k < 3; ++k) {
      const float c = std::clamp(rgba[4 * p + static_cast<std::size_t>(k)], 0.0f, 1.0f);
      const float encoded = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
      bytes[3 * p + static_cast<std::size_t>(k)] = static_cast<unsigned char>(std::lround(255.0f * encoded));
    }
  }
  file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(file.flush());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) == "--help") {
    std::printf("usage: carbtf_example_host material.cbtf [frames=8] [out=example_host.ppm]\n");
    return argc < 2 ? 2 : 0;
  }
  try {
    carbtf::Material material;
    if (const carbtf::Status s = carbtf::read_material_file(argv[1], material); !s.ok()) {
      std::fprintf(stderr, "carbtf_example_host: error: %s\n", s.message().c_str());
      return 1;
    }
    const int frames = argc > 2 ? std::max(1, std::atoi(argv[2])) : 8;
    const std::string out = argc > 3 ? argv[3] : "example_host.ppm";
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
    if (!write_ppm(out, pixels, engine.width(), engine.height())) {
      std::fprintf(stderr, "carbtf_example_host: error: %s: cannot write the image\n", out.c_str());
      return 1;
    }
    std::printf("wrote %s\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "carbtf_example_host: error: %s\n", e.what());
    return 1;
  }
}
