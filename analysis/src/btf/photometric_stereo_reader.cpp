// Photometric-stereo sets (one view, N lights), in the layout common benchmarks use.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "../text.hpp"
#include "carbtf/analysis/btf/btf_reader.hpp"
#include "carbtf/analysis/image_io.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "image_sources.hpp"

namespace carbtf {

namespace fs = std::filesystem;

namespace {

// Non-empty, non-comment lines of a text file, each split into whitespace-separated numbers; exactly
// `columns` per line unless `columns_alt` also allows another count.
std::vector<std::vector<double>> read_number_lines(const fs::path& path, std::size_t columns,
                                                   std::size_t columns_alt) {
  std::ifstream file(path);
  if (!file) throw InputError(path, "cannot open");
  std::vector<std::vector<double>> rows;
  std::string text;
  for (std::size_t line = 1; std::getline(file, text); ++line) {
    const auto start = text.find_first_not_of(" \t\r");
    if (start == std::string::npos || text[start] == '#') continue;
    std::istringstream in(text);
    std::vector<double> values;
    std::string token;
    while (in >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size() || !std::isfinite(v)) {
        throw InputError(path.string() + ":" + std::to_string(line), "'" + token + "' is not a number");
      }
      values.push_back(v);
    }
    if (values.size() != columns && values.size() != columns_alt) {
      throw InputError(
          path.string() + ":" + std::to_string(line),
          "expected " + std::to_string(columns) + " numbers, found " + std::to_string(values.size()));
    }
    rows.push_back(std::move(values));
  }
  return rows;
}

}  // namespace

BtfDataset read_photometric_stereo(const fs::path& folder, const BtfLoadOptions& options,
                                   std::vector<std::string>& warnings) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) throw InputError(folder, "not a folder");
  const fs::path light_file = folder / "light_directions.txt";
  const auto light_rows = read_number_lines(light_file, 3, 3);

  std::vector<fs::path> images;
  if (fs::exists(folder / "filenames.txt", ec)) {
    std::ifstream names(folder / "filenames.txt");
    std::string name;
    while (std::getline(names, name)) {
      while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
      if (!name.empty()) images.push_back(folder / name);
    }
  } else {
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = detail::to_lower(entry.path().filename().string());
      if (!entry.is_regular_file() || !is_supported_image_extension(entry.path())) continue;
      if (name.starts_with("mask.") || name.starts_with("normal") || name.starts_with(".")) continue;
      images.push_back(entry.path());
    }
    std::sort(images.begin(), images.end());
  }
  if (images.empty()) throw InputError(folder, "no images next to light_directions.txt");
  if (light_rows.size() != images.size()) {
    throw InputError(light_file, "has " + std::to_string(light_rows.size()) +
                                     " light directions but there are " + std::to_string(images.size()) +
                                     " images");
  }

  std::vector<Direction> lights;
  for (std::size_t i = 0; i < light_rows.size(); ++i) {
    const auto& v = light_rows[i];
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (length < 1e-12)
      throw InputError(light_file.string() + ":" + std::to_string(i + 1), "zero light direction");
    if (v[2] <= 0) {
      throw InputError(light_file.string() + ":" + std::to_string(i + 1),
                       "light direction below the horizon (z <= 0)");
    }
    lights.push_back(Direction::from_vector({v[0], v[1], v[2]}));
  }

  std::vector<std::array<float, 3>> intensities;
  const fs::path intensity_file = folder / "light_intensities.txt";
  if (fs::exists(intensity_file, ec)) {
    const auto rows = read_number_lines(intensity_file, 3, 1);
    if (rows.size() != images.size()) {
      throw InputError(intensity_file, "has " + std::to_string(rows.size()) + " lines but there are " +
                                           std::to_string(images.size()) + " images");
    }
    for (std::size_t i = 0; i < rows.size(); ++i) {
      std::array<float, 3> rgb{};
      for (int k = 0; k < 3; ++k) rgb[k] = static_cast<float>(rows[i][rows[i].size() == 1 ? 0 : k]);
      if (*std::min_element(rgb.begin(), rgb.end()) <= 0) {
        throw InputError(intensity_file.string() + ":" + std::to_string(i + 1),
                         "intensities must be positive");
      }
      intensities.push_back(rgb);
    }
  }

  std::vector<detail::ImageSource> sources;
  for (std::uint32_t i = 0; i < images.size(); ++i) {
    sources.push_back({images[i].string(), [path = images[i]] { return read_file_bytes(path); }, {i, 0}});
  }
  detail::ImageAdjustment adjust;
  if (!intensities.empty()) {
    // Dividing by the light's intensity needs linear values; the dataset then stores half floats.
    adjust = [&intensities](const detail::ImageSource& source, RgbImage& image) {
      if (!image.linear) {
        image.linear_rgb.resize(image.srgb8.size());
        for (std::size_t i = 0; i < image.srgb8.size(); ++i)
          image.linear_rgb[i] = srgb_to_linear(image.srgb8[i] / 255.0f);
        image.srgb8.clear();
        image.linear = true;
      }
      const auto& scale = intensities[source.pair.light];
      for (std::size_t i = 0; i < image.linear_rgb.size(); ++i) image.linear_rgb[i] /= scale[i % 3];
    };
  }
  BtfDataset dataset =
      detail::decode_sources(sources, std::move(lights), {Direction{}},
                             "photometric-stereo set " + folder.string(), options, warnings, adjust);

  const fs::path mask_file = folder / "mask.png";
  if (fs::exists(mask_file, ec)) {
    const RgbImage mask = decode_rgb_image(mask_file.string(), read_file_bytes(mask_file));
    if (mask.width != dataset.width() || mask.height != dataset.height()) {
      throw InputError(mask_file, "mask is " + std::to_string(mask.width) + "x" +
                                      std::to_string(mask.height) + " but the images are " +
                                      std::to_string(dataset.width()) + "x" +
                                      std::to_string(dataset.height()));
    }
    dataset.mask.resize(dataset.pixel_count());
    for (std::size_t i = 0; i < dataset.mask.size(); ++i) {
      dataset.mask[i] = mask.linear ? (mask.linear_rgb[i * 3] > 0 ? 255 : 0) : mask.srgb8[i * 3];
    }
  }
  return dataset;
}

}  // namespace carbtf
