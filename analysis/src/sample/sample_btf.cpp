#include "carbtf/analysis/sample/sample_btf.hpp"

#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"

namespace carbtf {

void write_sample_btf(const Surface& surface, const std::filesystem::path& output,
                      const std::string& extension, bool zip) {
  Ubo2003Writer writer(output, extension, zip);
  const auto& directions = ubo2003_directions();
  render_btf(surface, directions, directions, {},
             [&](std::uint32_t light, std::uint32_t view, std::span<const float> image) {
               writer.write(light, view, image, surface.size, surface.size);
             });
  writer.finish();
}

}  // namespace carbtf
