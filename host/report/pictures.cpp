#include "report/pictures.hpp"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "carbtf/analysis/image_io.hpp"

namespace carbtf::cli {

std::vector<float> channels_to_rgb(const std::vector<float>& values, std::uint32_t channels,
                                   std::size_t pixels) {
  std::vector<float> rgb(pixels * 3);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (std::uint32_t c = 0; c < 3; ++c) {
      rgb[p * 3 + c] = channels == 1 ? values[p] : c < channels ? values[p * channels + c] : 0.0f;
    }
  }
  return rgb;
}

std::vector<float> rendered_rgb(const RenderedImage& frame) {
  const std::size_t pixels = std::size_t{frame.width} * frame.height;
  std::vector<float> rgba(pixels * 4);
  std::memcpy(rgba.data(), frame.bytes.data(), std::min(frame.bytes.size(), rgba.size() * sizeof(float)));
  std::vector<float> rgb(pixels * 3);
  for (std::size_t p = 0; p < pixels; ++p) {
    for (int k = 0; k < 3; ++k) rgb[3 * p + k] = rgba[4 * p + k];
  }
  return rgb;
}

std::string two_digits(std::size_t value) {
  const std::string digits = std::to_string(value);
  return digits.size() < 2 ? "0" + digits : digits;
}

std::vector<float> side_by_side(const std::vector<float>& left, const std::vector<float>& right,
                                std::uint32_t width, std::uint32_t height) {
  std::vector<float> both(std::size_t{width} * height * 6);
  for (std::uint32_t y = 0; y < height; ++y) {
    std::copy_n(&left[std::size_t{y} * width * 3], width * 3, &both[std::size_t{y} * width * 6]);
    std::copy_n(&right[std::size_t{y} * width * 3], width * 3, &both[std::size_t{y} * width * 6 + width * 3]);
  }
  return both;
}

void write_png_and_exr(const std::filesystem::path& folder, const std::string& stem,
                       const std::vector<float>& values, std::uint32_t channels, std::uint32_t width,
                       std::uint32_t height) {
  const std::vector<float> rgb = channels_to_rgb(values, channels, std::size_t{width} * height);
  write_rgb_image(folder / (stem + ".png"), rgb, width, height, true);
  write_rgb_image(folder / (stem + ".exr"), rgb, width, height, true);
}

std::string describe_weights(const PairWeights& weights) {
  std::ostringstream text;
  for (std::size_t k = 0; k < weights.weight.size(); ++k) {
    if (weights.weight[k] == 0.0f) continue;
    text << " (light " << weights.light[k] << ", view " << weights.view[k] << ") " << weights.weight[k];
  }
  return text.str();
}

}  // namespace carbtf::cli
