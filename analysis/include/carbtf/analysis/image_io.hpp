// Writing single-channel float fields and RGB images to disk through OpenImageIO.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "carbtf/engine/file_output.hpp"

namespace carbtf {

// How a float field is mapped to an 8-bit file (EXR, TIFF, PFM keep the floats as they are).
struct FieldToDisplay {
  float low = -4.0f;  // maps to 0
  float high = 4.0f;  // maps to 255
};

// Writes `values` (width * height, row 0 at the top) to `path`; the format follows the extension:
// .png/.jpg/.jpeg/.bmp get 8-bit grey through `display`, .exr/.tif/.tiff/.pfm get 32-bit float.
// Creates missing parent folders. Throws InputError naming the file.
void write_field_image(const std::filesystem::path& path, std::span<const float> values, std::uint32_t width,
                       std::uint32_t height, const FieldToDisplay& display = {});

// Creates `folder` and its parents if missing; throws InputError naming it when it cannot.
void create_folder(const std::filesystem::path& folder);

// True when write_field_image() knows the extension of `path`.
bool is_supported_image_extension(const std::filesystem::path& path);
// True when `path` names a format that keeps 32-bit floats (.exr, .tif, .tiff, .pfm).
bool is_float_image_extension(const std::filesystem::path& path);

// A decoded RGB image: 8-bit sRGB (8-bit JPEG, PNG, BMP) or linear float (EXR, float TIFF, PFM, and
// 16-bit integer images, which photometric captures store linearly).
struct RgbImage {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool linear = false;              // which of the two vectors holds the pixels
  std::vector<std::uint8_t> srgb8;  // width * height * 3 when !linear
  std::vector<float> linear_rgb;    // width * height * 3 when linear
  // How many times the stored colour's resolution halves below its brightness's: 1 for a JPEG's 4:2:0,
  // 4:2:2 or 4:4:0 chroma, 2 for 4:1:1, 0 for full-resolution colour (4:4:4 JPEG, PNG, EXR, ...).
  std::uint32_t chroma_halvings = 0;
};

// What an image of a dataset must be, checked from its header before any pixel is decoded.
struct ImageShape {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  bool linear = false;  // RgbImage::linear
};

// Decodes an image held in memory; `name` (a path or an archive entry) names it in errors and its
// extension picks the decoder. Grey images become RGB; alpha is dropped. Throws InputError for
// anything that is not a complete, finite image: unknown or non-image content, corrupt or truncated
// data, NaN or Inf samples, a zero size or more than 4096 x 4096 pixels, or (when `expected` is given)
// another size or encoding; sizes are checked from the header, before the pixels are decoded.
RgbImage decode_rgb_image(const std::string& name, std::span<const std::byte> bytes,
                          const ImageShape* expected = nullptr);

// Reads a whole regular file of at most 256 MiB into memory; throws InputError naming the file when it
// cannot.
std::vector<std::byte> read_file_bytes(const std::filesystem::path& path);

// Encodes RGB (width * height * 3 floats) for a file named `name`: 8-bit for .jpg/.png (JPEG quality
// 95), 32-bit float for .exr. 8-bit files get the sRGB transfer function when `srgb_encode` (colours),
// and the values as they are, clamped to [0, 1], otherwise (data such as normal maps).
std::vector<std::byte> encode_rgb_image(const std::string& name, std::span<const float> rgb,
                                        std::uint32_t width, std::uint32_t height, bool srgb_encode = true);

// encode_rgb_image() written to `path` (parent folders created); throws InputError naming the file.
void write_rgb_image(const std::filesystem::path& path, std::span<const float> rgb, std::uint32_t width,
                     std::uint32_t height, bool srgb_encode = true);

// `bytes` (or `text`) written to `path` whole or not at all (write_file_whole() in the engine's
// file_output.hpp), parent folders created; InputError naming the file when that fails or when `path`
// is something other than a regular file (a device, FIFO, socket or folder is never replaced).
void write_output_file(const std::filesystem::path& path, std::span<const std::byte> bytes,
                       Flush flush = Flush::each_file);
void write_output_file(const std::filesystem::path& path, std::string_view text);

}  // namespace carbtf
