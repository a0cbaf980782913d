#include "carbtf/analysis/btf/btf_dataset.hpp"

#include <Imath/half.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "carbtf/analysis/input_error.hpp"

namespace carbtf {

const char* color_encoding_name(ColorEncoding encoding) {
  switch (encoding) {
    case ColorEncoding::srgb8:
      return "8-bit sRGB (linearised on load)";
    case ColorEncoding::linear_half:
      return "linear float (stored as half)";
    case ColorEncoding::decoded:
      return "linear float (decompressed per image on access)";
  }
  return "unknown";
}

float srgb_to_linear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

float linear_to_srgb(float linear) {
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

namespace {

std::uint8_t srgb8_by_power(float linear) {
  return static_cast<std::uint8_t>(std::lround(linear_to_srgb(linear) * 255.0f));
}

// Floats of [0, 1] in buckets of their top 16 bits (sign, exponent, 7 mantissa bits): each bucket is
// narrower than the distance between two steps of the code (checked when the table is built), so a
// bucket holds the code at its start and at most one step, the least float whose code is one more.
// Non-negative floats order as their bit patterns do, so a step is found by bisection over those.
constexpr std::uint32_t kSrgb8BucketShift = 16;

struct Srgb8CodeTable {
  std::vector<std::uint8_t> base;
  std::vector<float> step;  // +infinity where the bucket holds none
};

const Srgb8CodeTable& srgb8_code_table() {
  static const Srgb8CodeTable table = [] {
    const std::uint32_t last = std::bit_cast<std::uint32_t>(1.0f) >> kSrgb8BucketShift;
    Srgb8CodeTable t;
    t.base.resize(last + 1);
    t.step.assign(last + 1, std::numeric_limits<float>::infinity());
    for (std::uint32_t b = 0; b <= last; ++b) {
      std::uint32_t low = b << kSrgb8BucketShift;
      const std::uint32_t end =
          std::min((b + 1) << kSrgb8BucketShift, std::bit_cast<std::uint32_t>(1.0f) + 1);
      const int first = srgb8_by_power(std::bit_cast<float>(low));
      const int final = srgb8_by_power(std::bit_cast<float>(end - 1));
      t.base[b] = static_cast<std::uint8_t>(first);
      if (final == first) continue;
      if (final != first + 1) throw std::logic_error("linear_to_srgb8: a bucket holds two steps of the code");
      std::uint32_t high = end - 1;  // the step lies in (low, high]
      while (high - low > 1) {
        const std::uint32_t middle = low + (high - low) / 2;
        (srgb8_by_power(std::bit_cast<float>(middle)) > first ? high : low) = middle;
      }
      t.step[b] = std::bit_cast<float>(high);
    }
    return t;
  }();
  return table;
}

}  // namespace

std::uint8_t linear_to_srgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // NaN too
  const float v = std::min(linear, 1.0f);
  const Srgb8CodeTable& table = srgb8_code_table();
  const std::uint32_t bucket = std::bit_cast<std::uint32_t>(v) >> kSrgb8BucketShift;
  return static_cast<std::uint8_t>(table.base[bucket] + (v >= table.step[bucket] ? 1 : 0));
}

namespace {

const std::array<float, 256>& srgb8_table() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgb_to_linear(static_cast<float>(i) / 255.0f);
    return t;
  }();
  return table;
}

}  // namespace

BtfDataset::BtfDataset(std::vector<Direction> lights, std::vector<Direction> views, std::uint32_t width,
                       std::uint32_t height, ColorEncoding encoding)
    : lights_(std::move(lights)),
      views_(std::move(views)),
      width_(width),
      height_(height),
      encoding_(encoding) {
  const std::size_t slots = lights_.size() * views_.size();
  if (encoding_ == ColorEncoding::srgb8) {
    srgb_.resize(slots);
  } else {
    half_.resize(slots);
  }
}

BtfDataset::BtfDataset(std::vector<Direction> lights, std::vector<Direction> views, std::uint32_t width,
                       std::uint32_t height, std::shared_ptr<const ImageDecoder> decoder)
    : lights_(std::move(lights)),
      views_(std::move(views)),
      width_(width),
      height_(height),
      encoding_(ColorEncoding::decoded),
      decoder_(std::move(decoder)) {
  if (!decoder_) throw std::invalid_argument("BtfDataset: no image decoder");
}

std::size_t BtfDataset::slot(LightView pair) const {
  if (pair.light >= lights_.size() || pair.view >= views_.size())
    throw std::out_of_range("BTF pair out of range");
  return std::size_t{pair.light} * views_.size() + pair.view;
}

bool BtfDataset::has_image(LightView pair) const {
  const std::size_t s = slot(pair);
  switch (encoding_) {
    case ColorEncoding::srgb8:
      return !srgb_[s].empty();
    case ColorEncoding::linear_half:
      return !half_[s].empty();
    case ColorEncoding::decoded:
      return true;
  }
  return false;
}

std::vector<LightView> BtfDataset::pairs_where_present(bool present) const {
  std::vector<LightView> pairs;
  for (std::uint32_t l = 0; l < lights_.size(); ++l) {
    for (std::uint32_t v = 0; v < views_.size(); ++v) {
      if (has_image({l, v}) == present) pairs.push_back({l, v});
    }
  }
  return pairs;
}

std::vector<LightView> BtfDataset::present_pairs() const {
  return pairs_where_present(true);
}
std::vector<LightView> BtfDataset::missing_pairs() const {
  return pairs_where_present(false);
}

void BtfDataset::set_srgb8(LightView pair, std::vector<std::uint8_t> pixels) {
  if (encoding_ != ColorEncoding::srgb8) throw std::invalid_argument("set_srgb8 on a linear dataset");
  if (pixels.size() != pixel_count() * 3)
    throw std::invalid_argument("image size does not match the dataset");
  srgb_[slot(pair)] = std::move(pixels);
}

void BtfDataset::set_linear(LightView pair, std::span<const float> rgb) {
  if (encoding_ != ColorEncoding::linear_half) throw std::invalid_argument("set_linear on an 8-bit dataset");
  if (rgb.size() != pixel_count() * 3) throw std::invalid_argument("image size does not match the dataset");
  std::vector<std::uint16_t> halves(rgb.size());
  for (std::size_t i = 0; i < rgb.size(); ++i) halves[i] = Imath::half(rgb[i]).bits();
  half_[slot(pair)] = std::move(halves);
}

void BtfDataset::set_linear_half(LightView pair, std::vector<std::uint16_t> halves) {
  if (encoding_ != ColorEncoding::linear_half)
    throw std::invalid_argument("set_linear_half on a dataset not of halves");
  if (halves.size() != pixel_count() * 3)
    throw std::invalid_argument("image size does not match the dataset");
  half_[slot(pair)] = std::move(halves);
}

void BtfDataset::linear_rgb(LightView pair, std::span<float> out) const {
  const std::size_t s = slot(pair);
  if (out.size() < pixel_count() * 3) throw std::invalid_argument("output span too small for the image");
  if (encoding_ == ColorEncoding::decoded) {
    decoder_->decode(pair, out.first(pixel_count() * 3));
  } else if (encoding_ == ColorEncoding::srgb8) {
    const auto& pixels = srgb_[s];
    if (pixels.empty()) throw std::out_of_range("BTF image missing for this light/view pair");
    const auto& table = srgb8_table();
    for (std::size_t i = 0; i < pixels.size(); ++i) out[i] = table[pixels[i]];
  } else {
    const auto& halves = half_[s];
    if (halves.empty()) throw std::out_of_range("BTF image missing for this light/view pair");
    for (std::size_t i = 0; i < halves.size(); ++i) {
      Imath::half h;
      h.setBits(halves[i]);
      out[i] = static_cast<float>(h);
    }
  }
}

std::size_t BtfDataset::storage_bytes() const {
  std::size_t bytes = decoder_ ? decoder_->storage_bytes() : 0;
  for (const auto& image : srgb_) bytes += image.size();
  for (const auto& image : half_) bytes += image.size() * sizeof(std::uint16_t);
  return bytes;
}

namespace {

// Within 1e-4 rad; the azimuth modulo a turn, and not at all at the pole where it means nothing.
bool same_directions(const std::vector<Direction>& measured, const std::vector<MaterialDirection>& model) {
  if (measured.size() != model.size()) return false;
  for (std::size_t i = 0; i < model.size(); ++i) {
    if (std::abs(measured[i].theta - model[i].theta) > 1e-4) return false;
    if (measured[i].theta > 1e-6 &&
        std::abs(std::remainder(measured[i].phi - model[i].phi, 2 * std::numbers::pi)) > 1e-4) {
      return false;
    }
  }
  return true;
}

}  // namespace

void check_direction_table(const std::string& input, std::size_t lights, std::size_t views,
                           std::size_t measured) {
  for (const auto& [count, what] : {std::pair{lights, "light"}, std::pair{views, "view"}}) {
    if (count > kMaxDatasetDirections) {
      throw InputError(input, "has more than " + std::to_string(kMaxDatasetDirections) + " distinct " + what +
                                  " directions; carbtf reads at most " +
                                  std::to_string(kMaxDatasetDirections));
    }
  }
  const std::size_t table = lights * views;
  if (table > kSparseTablePairs && measured * kMinMeasuredShareDenominator < table) {
    throw InputError(
        input, "measures " + std::to_string(measured) + " of the " + std::to_string(lights) + " x " +
                   std::to_string(views) + " = " + std::to_string(table) +
                   " light/view pairs its directions span; in a table of over " +
                   std::to_string(kSparseTablePairs) + " pairs carbtf needs at least 1 in " +
                   std::to_string(kMinMeasuredShareDenominator) + " (" +
                   std::to_string((table + kMinMeasuredShareDenominator - 1) / kMinMeasuredShareDenominator) +
                   ") measured");
  }
}

void require_directions_of(const BtfDataset& dataset, const Material& material, const std::string& input) {
  if (!same_directions(dataset.lights(), material.lights) ||
      !same_directions(dataset.views(), material.views)) {
    throw InputError(
        input, "its light and view directions are not the material's (" +
                   std::to_string(dataset.lights().size()) + " x " + std::to_string(dataset.views().size()) +
                   " against " + std::to_string(material.lights.size()) + " x " +
                   std::to_string(material.views.size()) + "); give the BTF the material was analysed from");
  }
}

}  // namespace carbtf
