// A measured BTF: one RGB image per (light direction, view direction) pair, over any direction sets.
//
// Pixels are kept as the source stored them, to fit a full 81 x 81 x 256^2 material in about 1.3 GB:
// 8-bit sRGB for JPEG/PNG sources, IEEE half for linear (EXR, UBO2014 raw) sources. A compressed source
// (UBO2014 DFMF, 151 x 151 x 400^2: 22 GB as half) is not expanded at all: an ImageDecoder rebuilds each
// image when it is asked for. The model always sees linear float RGB: linear_rgb() converts on access. Images
// are row-major, row 0 at the top, RGB interleaved. Pairs may be missing (partial datasets). Thread safety:
// concurrent reads are safe; set_* calls on different pairs may run concurrently, on the same pair they must
// not.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "carbtf/analysis/btf/directions.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf {

enum class ColorEncoding {
  srgb8,        // 8-bit, sRGB transfer function (JPEG, PNG)
  linear_half,  // linear light, 16-bit float (EXR, UBO2014 raw)
  decoded,      // linear light, rebuilt per image from a compressed file (UBO2014 DFMF)
};
const char* color_encoding_name(ColorEncoding encoding);

struct LightView {
  std::uint32_t light = 0;
  std::uint32_t view = 0;
  bool operator==(const LightView&) const = default;
};

// Rebuilds images on demand from a compressed file held in memory. decode() is called from several
// threads at once; it throws InputError when the file's data decodes to a value that is not finite.
class ImageDecoder {
 public:
  virtual ~ImageDecoder() = default;
  // Every pair of the table, width * height * 3 floats of linear RGB.
  virtual void decode(LightView pair, std::span<float> linear_rgb) const = 0;
  virtual std::size_t storage_bytes() const = 0;
};

class BtfDataset {
 public:
  BtfDataset() = default;
  BtfDataset(std::vector<Direction> lights, std::vector<Direction> views, std::uint32_t width,
             std::uint32_t height, ColorEncoding encoding);
  // A dataset whose every image is rebuilt by `decoder` (encoding `decoded`; the set_* calls refuse).
  BtfDataset(std::vector<Direction> lights, std::vector<Direction> views, std::uint32_t width,
             std::uint32_t height, std::shared_ptr<const ImageDecoder> decoder);

  const std::vector<Direction>& lights() const { return lights_; }
  const std::vector<Direction>& views() const { return views_; }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  ColorEncoding encoding() const { return encoding_; }
  std::size_t pixel_count() const { return std::size_t{width_} * height_; }

  bool has_image(LightView pair) const;
  std::vector<LightView> present_pairs() const;
  std::vector<LightView> missing_pairs() const;

  // Stores an image: width * height * 3 bytes of sRGB (srgb8 datasets) or floats of linear RGB
  // (linear_half datasets; converted to half). Throws std::invalid_argument on a size mismatch.
  void set_srgb8(LightView pair, std::vector<std::uint8_t> pixels);
  void set_linear(LightView pair, std::span<const float> rgb);
  // Stores an image of IEEE half bit patterns as they are (linear_half datasets).
  void set_linear_half(LightView pair, std::vector<std::uint16_t> halves);

  // Linear RGB of a stored image into `out` (width * height * 3 floats). Throws std::out_of_range if
  // the pair is missing.
  void linear_rgb(LightView pair, std::span<float> out) const;

  // Bytes held by pixel storage.
  std::size_t storage_bytes() const;

  // Where the data came from, e.g. "UBO2003 folder /data/wool"; shown by `carbtf info`.
  std::string source;
  // Optional validity mask, width * height, non-zero where the sample is (photometric-stereo sets).
  std::vector<std::uint8_t> mask;
  // How many times the stored images' colour resolution halves below their brightness's (the first
  // image's RgbImage::chroma_halvings: 1 for JPEGs with 4:2:0 chroma, as UBO2003's; 0 for full-resolution
  // colour). The analysis reads the relief's chroma that much coarser (model/relief_chroma.hpp).
  std::uint32_t chroma_halvings = 0;

 private:
  std::size_t slot(LightView pair) const;
  std::vector<LightView> pairs_where_present(bool present) const;

  std::vector<Direction> lights_;
  std::vector<Direction> views_;
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
  ColorEncoding encoding_ = ColorEncoding::srgb8;
  std::vector<std::vector<std::uint8_t>> srgb_;   // per slot, empty when missing
  std::vector<std::vector<std::uint16_t>> half_;  // per slot, empty when missing
  std::shared_ptr<const ImageDecoder> decoder_;   // every slot, when set
};

// The largest direction sets a dataset may have, and how sparse a large light x view table may be. The
// table has a slot per pair and every missing pair is filled from the measured ones, so a manifest of
// 10,000 images at 10,000 distinct directions each would otherwise ask for a table of 10^8 pairs
// (gigabytes) before its first image is read. UBO2003 has 81 x 81, UBO2014 151 x 151: any table up to
// kSparseTablePairs may be as sparse as it likes; a larger one must be at least a quarter measured.
inline constexpr std::size_t kMaxDatasetDirections = 1024;
inline constexpr std::size_t kSparseTablePairs = 65536;
inline constexpr std::size_t kMinMeasuredShareDenominator = 4;  // at least 1 pair in 4 of a larger table

// Throws InputError naming `input`, with the counts found and the limit, unless `lights` and `views`
// are each at most kMaxDatasetDirections and a table of more than kSparseTablePairs pairs has at least
// a quarter of them `measured`. The readers call it before they allocate anything for the table.
void check_direction_table(const std::string& input, std::size_t lights, std::size_t views,
                           std::size_t measured);

// Throws InputError naming `input` unless the dataset's light and view directions are the material's
// (within 1e-4 rad; the azimuth modulo a turn, and not at all at the pole): the check before a model
// is compared with a measurement.
void require_directions_of(const BtfDataset& dataset, const Material& material, const std::string& input);

// The sRGB transfer function and its inverse (IEC 61966-2-1), on [0, 1].
float srgb_to_linear(float encoded);
float linear_to_srgb(float linear);
// The 8-bit sRGB code of a linear value: exactly lround(255 * linear_to_srgb(clamp(linear, 0, 1))), NaN
// giving 0, read from a table of where that expression's code steps (found once, by bisection on the
// expression itself) instead of computed by a power per value.
std::uint8_t linear_to_srgb8(float linear);

}  // namespace carbtf
