// What the BTF reader tests share (test_btf_*.cpp): files written for UBO2003 pairs, the rendered leather
// sample written as a folder or zip, and the check that an input error names the file and the problem.
#pragma once

#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <zip.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include <cmath>
#include <filesystem>

#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include "scratch_folder.hpp"
#include "test_materials.hpp"

#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/btf/ubo2003_names.hpp"
#include "carbtf/analysis/btf/ubo2003_writer.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/analysis/sample/height_field_renderer.hpp"
#include "carbtf/analysis/sample/sample_materials.hpp"
#include "carbtf/engine/material/material_file.hpp"  // crc32, the PNG chunk checksum too

namespace carbtf::btf_test_files {

namespace fs = std::filesystem;
using test::scratch_folder;

inline const BtfLoadOptions kQuiet{0, false};

// A uniform image file named for UBO2003 pair (light, view).
inline void write_uniform(const fs::path& path, std::uint32_t size, float value) {
  std::vector<float> rgb(std::size_t{size} * size * 3, value);
  write_rgb_image(path, rgb, size, size);
}

inline std::string name_of(std::uint32_t light, std::uint32_t view, const std::string& ext = ".png") {
  return ubo2003_file_name(light, view, ext);
}

// Requires load_btf(path) to throw InputError whose message contains every fragment.
inline void require_input_error(const fs::path& path, const std::vector<std::string>& fragments) {
  std::vector<std::string> warnings;
  try {
    load_btf(path, kQuiet, warnings);
    FAIL("loading " << path << " did not fail");
  } catch (const InputError& e) {
    const std::string message = e.what();
    INFO("message: " << message);
    for (const std::string& fragment : fragments) CHECK_THAT(message, Catch::Contains(fragment));
  }
}

struct RenderedSample {
  Surface surface;
  std::map<std::uint32_t, std::vector<float>> images;  // key light * 81 + view
};

inline const RenderedSample& rendered_leather() {
  static const RenderedSample sample = [] {
    RenderedSample s;
    s.surface = make_sample_surface("leather", 16, 5);
    std::mutex mutex;
    RenderOptions options;
    options.progress = false;
    render_btf(s.surface, ubo2003_directions(), ubo2003_directions(), options,
               [&](std::uint32_t l, std::uint32_t v, std::span<const float> image) {
                 std::lock_guard<std::mutex> lock(mutex);
                 s.images[l * 81 + v].assign(image.begin(), image.end());
               });
    return s;
  }();
  return sample;
}

inline void write_sample(const fs::path& out, const std::string& extension, bool zip) {
  const RenderedSample& s = rendered_leather();
  Ubo2003Writer writer(out, extension, zip);
  for (const auto& [key, image] : s.images) writer.write(key / 81, key % 81, image, 16, 16);
  writer.finish();
}

// Largest and RMS difference, in 8-bit sRGB steps, between a loaded image and the rendered one.
inline void srgb_difference(const BtfDataset& dataset, LightView pair, const std::vector<float>& rendered,
                            double& max_steps, double& rms_steps) {
  std::vector<float> loaded(dataset.pixel_count() * 3);
  dataset.linear_rgb(pair, loaded);
  double sum = 0;
  max_steps = 0;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    const double a = linear_to_srgb(loaded[i]) * 255.0;
    const double b = linear_to_srgb(std::clamp(rendered[i], 0.0f, 1.0f)) * 255.0;
    max_steps = std::max(max_steps, std::abs(a - b));
    sum += (a - b) * (a - b);
  }
  rms_steps = std::sqrt(sum / static_cast<double>(loaded.size()));
}

}  // namespace carbtf::btf_test_files
