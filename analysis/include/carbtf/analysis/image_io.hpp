// Writing single-channel float fields and RGB images to disk through OpenImageIO.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace carbtf {

// How a float field is mapped to an 8-bit file (EXR, TIFF, PFM keep the floats as they are).
struct FieldToDisplay {
  float low = -4.0f;   // maps to 0
  float high = 4.0f;   // maps to 255
};

// Writes `values` (width * height, row 0 at the top) to `path`; the format follows the extension:
// .png/.jpg/.jpeg/.bmp get 8-bit grey through `display`, .exr/.tif/.tiff/.pfm get 32-bit float.
// Creates missing parent folders. Returns false and fills `error` with one line naming the file.
bool write_field_image(const std::filesystem::path& path, std::span<const float> values, std::uint32_t width,
                       std::uint32_t height, const FieldToDisplay& display, std::string& error);

// True when write_field_image() knows the extension of `path`.
bool is_supported_image_extension(const std::filesystem::path& path);
// True when `path` names a format that keeps 32-bit floats (.exr, .tif, .tiff, .pfm).
bool is_float_image_extension(const std::filesystem::path& path);

}  // namespace carbtf
