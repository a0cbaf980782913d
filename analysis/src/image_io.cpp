#include "carbtf/analysis/image_io.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <system_error>
#include <vector>

namespace carbtf {

namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool is_float_format(const std::string& ext) { return ext == ".exr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm"; }
bool is_8bit_format(const std::string& ext) {
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp";
}

}  // namespace

bool is_float_image_extension(const std::filesystem::path& path) { return is_float_format(lower_extension(path)); }

bool is_supported_image_extension(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return is_float_format(ext) || is_8bit_format(ext);
}

bool write_field_image(const std::filesystem::path& path, std::span<const float> values, std::uint32_t width,
                       std::uint32_t height, const FieldToDisplay& display, std::string& error) {
  const std::string ext = lower_extension(path);
  if (!is_supported_image_extension(path)) {
    error = path.string() + ": unsupported image extension '" + ext + "' (use .png, .jpg, .bmp, .exr, .tif or .pfm)";
    return false;
  }
  if (values.size() < std::size_t{width} * height || width == 0 || height == 0) {
    error = path.string() + ": no pixels to write";
    return false;
  }
  std::error_code ec;
  if (path.has_parent_path() && !std::filesystem::exists(path.parent_path())) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) {
      error = path.parent_path().string() + ": cannot create folder: " + ec.message();
      return false;
    }
  }
  auto output = OIIO::ImageOutput::create(path.string());
  if (!output) {
    error = path.string() + ": cannot write: " + OIIO::geterror();
    return false;
  }
  const bool as_float = is_float_format(ext);
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), 1,
                       as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
  if (!output->open(path.string(), spec)) {
    error = path.string() + ": cannot write: " + output->geterror();
    return false;
  }
  bool written = false;
  if (as_float) {
    written = output->write_image(OIIO::TypeDesc::FLOAT, values.data());
  } else {
    std::vector<std::uint8_t> bytes(std::size_t{width} * height);
    const float scale = 255.0f / (display.high - display.low);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      const float v = std::clamp((values[i] - display.low) * scale, 0.0f, 255.0f);
      bytes[i] = static_cast<std::uint8_t>(std::lround(v));
    }
    written = output->write_image(OIIO::TypeDesc::UINT8, bytes.data());
  }
  if (!written || !output->close()) {
    error = path.string() + ": write failed: " + output->geterror();
    return false;
  }
  return true;
}

}  // namespace carbtf
