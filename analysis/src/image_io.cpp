#include "carbtf/analysis/image_io.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>
#include <vector>

#include "carbtf/analysis/btf/btf_dataset.hpp"
#include "carbtf/analysis/input_error.hpp"
#include "carbtf/engine/file_output.hpp"
#include "text.hpp"

namespace carbtf {

namespace {

using detail::lower_extension;

bool is_float_format(const std::string& ext) {
  return ext == ".exr" || ext == ".tif" || ext == ".tiff" || ext == ".pfm";
}

// The OpenImageIO reader for each extension carbtf reads, or nullptr. Only that reader is tried:
// ImageInput::open() would otherwise try every installed reader on a file its own one refuses, FFmpeg's
// video readers included, which a hostile dataset has no business reaching (a manifest naming
// "c.png\0.qt" did, and FFmpeg leaked on it under the fuzzer).
const char* image_reader(const std::string& ext) {
  if (ext == ".png") return "png";
  if (ext == ".jpg" || ext == ".jpeg") return "jpeg";
  if (ext == ".bmp") return "bmp";
  if (ext == ".exr") return "openexr";
  if (ext == ".tif" || ext == ".tiff") return "tiff";
  if (ext == ".pfm") return "pnm";
  if (ext == ".webp") return "webp";  // the built-in sample materials' maps (assets/materials)
  return nullptr;
}

// Encodes `channels` interleaved samples per pixel of `type` in memory, for a file named `name`: the
// encoder follows the extension, and the file is written whole afterwards (write_output_file()).
std::vector<std::byte> encode_image(const std::string& name, const void* pixels, OIIO::TypeDesc type,
                                    std::uint32_t width, std::uint32_t height, int channels) {
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  auto output = OIIO::ImageOutput::create(name);
  if (!output) throw InputError(name, "no encoder for this extension");
  output->set_ioproxy(&memory);
  OIIO::ImageSpec spec(static_cast<int>(width), static_cast<int>(height), channels, type);
  spec.attribute("CompressionQuality", 95);
  if (!output->open(name, spec)) throw InputError(name, "cannot encode: " + output->geterror());
  if (!output->write_image(type, pixels) || !output->close())
    throw InputError(name, "cannot encode: " + output->geterror());
  std::vector<std::byte> result(encoded.size());
  std::memcpy(result.data(), encoded.data(), encoded.size());
  return result;
}

// The engine's file errors start with the path, which InputError puts in front again.
std::string without_path(const std::string& message, const std::filesystem::path& path) {
  const std::string prefix = path.string() + ": ";
  return message.starts_with(prefix) ? message.substr(prefix.size()) : message;
}

}  // namespace

bool is_float_image_extension(const std::filesystem::path& path) {
  return is_float_format(lower_extension(path));
}

// Datasets and outputs: every format there is a reader for but WebP, which only the built-in assets use.
bool is_supported_image_extension(const std::filesystem::path& path) {
  const std::string ext = lower_extension(path);
  return image_reader(ext) != nullptr && ext != ".webp";
}

void create_folder(const std::filesystem::path& folder) {
  if (folder.empty()) return;
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) throw InputError(folder, "cannot create folder: " + ec.message());
}

void write_field_image(const std::filesystem::path& path, std::span<const float> values, std::uint32_t width,
                       std::uint32_t height, const FieldToDisplay& display) {
  const std::string ext = lower_extension(path);
  if (!is_supported_image_extension(path)) {
    throw InputError(path,
                     "unsupported image extension '" + ext + "' (use .png, .jpg, .bmp, .exr, .tif or .pfm)");
  }
  if (values.size() < std::size_t{width} * height || width == 0 || height == 0) {
    throw InputError(path, "no pixels to write");
  }
  const std::size_t count = std::size_t{width} * height;
  std::vector<std::byte> encoded;
  if (is_float_format(ext)) {
    encoded = encode_image(path.string(), values.data(), OIIO::TypeDesc::FLOAT, width, height, 1);
  } else {
    std::vector<std::uint8_t> bytes(count);
    const float scale = 255.0f / (display.high - display.low);
    for (std::size_t i = 0; i < count; ++i) {
      const float v = std::clamp((values[i] - display.low) * scale, 0.0f, 255.0f);
      bytes[i] = static_cast<std::uint8_t>(std::lround(v));
    }
    encoded = encode_image(path.string(), bytes.data(), OIIO::TypeDesc::UINT8, width, height, 1);
  }
  write_output_file(path, encoded);
}

}  // namespace carbtf

// ---- RGB images for BTF data ---------------------------------------------------------------------

namespace carbtf {

namespace {
// Larger than any BTF image; guards against hostile headers asking for absurd allocations.
// 4096 x 4096: BTF and photometric-stereo images are far smaller, and a header claiming more (a
// decompression bomb of a few KB) is refused before a pixel is decoded.
constexpr std::uint64_t kMaxImagePixels = 1ull << 24;
constexpr int kMaxImageChannels = 16;
// As for zip entries: no image file of a dataset comes near this.
constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{256} << 20;

// RgbImage::chroma_halvings of a JPEG's chroma subsampling as OpenImageIO names it (jpeg:subsampling): the
// axis halved most counts, so 4:2:0 (half along both) and 4:2:2 (half across) both halve once. No
// attribute (not a JPEG) or 4:4:4: full resolution.
std::uint32_t chroma_halvings(const std::string& subsampling) {
  if (subsampling == "4:2:0" || subsampling == "4:2:2" || subsampling == "4:4:0") return 1;
  if (subsampling == "4:1:1") return 2;
  return 0;
}
}  // namespace

std::vector<std::byte> read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) throw InputError(path, "not a readable file (no such file)");
  // A FIFO would block the reader until a writer came; a folder or device is no image either.
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, "is not a regular file (a folder, pipe or device), so it is not read");
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  if (!ec && file_bytes > kMaxImageFileBytes) {
    throw InputError(path, "is " + std::to_string(file_bytes >> 20) + " MiB; image files are read up to " +
                               std::to_string(kMaxImageFileBytes >> 20) + " MiB");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot open");
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  file.seekg(0, std::ios::beg);
  std::vector<std::byte> bytes(static_cast<std::size_t>(std::max<std::streamoff>(size, 0)));
  if (size > 0 && !file.read(reinterpret_cast<char*>(bytes.data()), size))
    throw InputError(path, "read failed");
  return bytes;
}

RgbImage decode_rgb_image(const std::string& name, std::span<const std::byte> bytes,
                          const ImageShape* expected) {
  if (bytes.empty()) throw InputError(name, "empty file, not an image");
  // IOMemReader takes a non-const pointer but only reads.
  OIIO::Filesystem::IOMemReader memory(const_cast<std::byte*>(bytes.data()), bytes.size());
  const char* reader = image_reader(lower_extension(name));
  if (reader == nullptr)
    throw InputError(
        name,
        "is not named as an image carbtf reads (.png, .jpg, .jpeg, .bmp, .exr, .tif, .tiff, .pfm, .webp)");
  auto input = OIIO::ImageInput::create(reader);
  if (!input)
    throw InputError(name,
                     std::string("no ") + reader + " reader in this OpenImageIO (" + OIIO::geterror() + ")");
  if (!input->set_ioproxy(&memory))
    throw InputError(name, std::string("the ") + reader + " reader cannot read from memory");
  OIIO::ImageSpec opened;
  if (!input->open(name, opened)) throw InputError(name, "not a readable image (" + input->geterror() + ")");
  const OIIO::ImageSpec& spec = input->spec();
  const std::string size_text = std::to_string(spec.width) + "x" + std::to_string(spec.height);
  if (spec.width <= 0 || spec.height <= 0) throw InputError(name, "implausible image size " + size_text);
  if (std::uint64_t(spec.width) * std::uint64_t(spec.height) > kMaxImagePixels) {
    throw InputError(name, "image header claims " + size_text +
                               " pixels; carbtf reads images up to 4096x4096 (16.8 M pixels)");
  }
  if (spec.depth > 1 || spec.nchannels < 1) throw InputError(name, "not a 2D colour or grey image");
  // Bounds the row buffer below, which holds every channel of one row.
  if (spec.nchannels > kMaxImageChannels) {
    throw InputError(name, "has " + std::to_string(spec.nchannels) +
                               " channels; carbtf reads images of up to " +
                               std::to_string(kMaxImageChannels) + " (grey, RGB or RGBA and extras)");
  }
  RgbImage image;
  image.width = static_cast<std::uint32_t>(spec.width);
  image.height = static_cast<std::uint32_t>(spec.height);
  image.chroma_halvings = chroma_halvings(spec.get_string_attribute("jpeg:subsampling"));
  const auto base = spec.format.basetype;
  const bool is_float = base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF ||
                        base == OIIO::TypeDesc::DOUBLE || base == OIIO::TypeDesc::UINT16 ||
                        base == OIIO::TypeDesc::INT16 || base == OIIO::TypeDesc::UINT32;
  image.linear = is_float;
  if (expected && (image.width != expected->width || image.height != expected->height)) {
    throw InputError(name, "image is " + size_text + " but the others are " +
                               std::to_string(expected->width) + "x" + std::to_string(expected->height));
  }
  if (expected && image.linear != expected->linear) {
    throw InputError(name, std::string("holds ") + (image.linear ? "linear float" : "8-bit sRGB") +
                               " pixels but the others hold " +
                               (expected->linear ? "linear float" : "8-bit sRGB"));
  }
  const std::size_t pixels = std::size_t{image.width} * image.height;
  // Colour images give RGB (alpha dropped); grey (+ alpha) images give their first channel, copied.
  const int channels = spec.nchannels >= 3 ? 3 : 1;
  // Row by row through read_scanline: read_image and read_scanlines allocate a conversion buffer sized
  // for a large image on every call (70 ms per 16x16 PNG under ASan, 15x the decode itself without).
  auto read_rows = [&](auto& values, OIIO::TypeDesc type) {
    using Value = typename std::decay_t<decltype(values)>::value_type;
    values.assign(pixels * 3, Value{});
    std::vector<Value> row(std::size_t(image.width) * std::size_t(spec.nchannels));
    for (std::uint32_t y = 0; y < image.height; ++y) {
      if (!input->read_scanline(spec.y + int(y), spec.z, type, row.data())) return false;
      Value* out = values.data() + std::size_t(y) * image.width * 3;
      for (std::uint32_t x = 0; x < image.width; ++x) {
        for (int c = 0; c < 3; ++c)
          out[x * 3 + c] = row[std::size_t(x) * spec.nchannels + (channels == 3 ? c : 0)];
      }
    }
    return true;
  };
  bool read = false;
  if (is_float) {
    read = read_rows(image.linear_rgb, OIIO::TypeDesc::FLOAT);
  } else {
    read = read_rows(image.srgb8, OIIO::TypeDesc::UINT8);
  }
  // Decoders such as libjpeg report truncation as a warning and still "succeed": any message fails.
  const std::string error = input->geterror();
  if (!read || !error.empty()) {
    throw InputError(name,
                     "corrupt or truncated image" + (error.empty() ? std::string() : " (" + error + ")"));
  }
  if (is_float) {
    for (std::size_t i = 0; i < image.linear_rgb.size(); ++i) {
      if (!std::isfinite(image.linear_rgb[i])) {
        throw InputError(name, std::string(std::isnan(image.linear_rgb[i]) ? "NaN" : "Inf") + " at pixel (" +
                                   std::to_string(i / 3 % image.width) + ", " +
                                   std::to_string(i / 3 / image.width) + ")");
      }
    }
  }
  return image;
}

std::vector<std::byte> encode_rgb_image(const std::string& name, std::span<const float> linear_rgb,
                                        std::uint32_t width, std::uint32_t height, bool srgb_encode) {
  if (is_float_image_extension(std::filesystem::path(name))) {
    return encode_image(name, linear_rgb.data(), OIIO::TypeDesc::FLOAT, width, height, 3);
  }
  std::vector<std::uint8_t> bytes(linear_rgb.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    bytes[i] = srgb_encode
                   ? linear_to_srgb8(linear_rgb[i])
                   : static_cast<std::uint8_t>(std::lround(std::clamp(linear_rgb[i], 0.0f, 1.0f) * 255.0f));
  }
  return encode_image(name, bytes.data(), OIIO::TypeDesc::UINT8, width, height, 3);
}

void write_rgb_image(const std::filesystem::path& path, std::span<const float> rgb, std::uint32_t width,
                     std::uint32_t height, bool srgb_encode) {
  write_output_file(path, encode_rgb_image(path.string(), rgb, width, height, srgb_encode));
}

void write_output_file(const std::filesystem::path& path, std::span<const std::byte> bytes, Flush flush) {
  // Checked before the parent folders are made, so that a refused path creates nothing.
  if (Status s = check_output_file(path.string()); !s.ok())
    throw InputError(path, without_path(s.message(), path));
  create_folder(path.parent_path());
  const Status s = write_file_whole(
      path.string(),
      std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()),
      flush);
  if (!s.ok()) throw InputError(path, without_path(s.message(), path));
}

void write_output_file(const std::filesystem::path& path, std::string_view text) {
  write_output_file(path,
                    std::span<const std::byte>(reinterpret_cast<const std::byte*>(text.data()), text.size()));
}

}  // namespace carbtf
