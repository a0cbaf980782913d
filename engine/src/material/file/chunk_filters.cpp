#include "material/file/chunk_filters.hpp"

#include <span>

#include "material/raster_prediction.hpp"

namespace carbtf::detail {

bool RasterLayout::fits(std::uint64_t size) const {
  if ((value_bytes != 1 && value_bytes != 2) || width == 0 || height == 0 || rasters == 0 ||
      rest_stride > kMaxFilterStride)
    return false;
  if (skip > size) return false;
  std::uint64_t room = (size - skip) / value_bytes;
  if (width > room) return false;
  room /= width;
  if (height > room) return false;
  return rasters <= room / height;
}

namespace {

// Stride 0 is no filter.
void apply_sub_filter(std::span<std::uint8_t> bytes, std::size_t stride) {
  if (stride == 0) return;
  for (std::size_t i = bytes.size(); i-- > stride;)
    bytes[i] = static_cast<std::uint8_t>(bytes[i] - bytes[i - stride]);
}
void undo_sub_filter(std::span<std::uint8_t> bytes, std::size_t stride) {
  if (stride == 0) return;
  for (std::size_t i = stride; i < bytes.size(); ++i)
    bytes[i] = static_cast<std::uint8_t>(bytes[i] + bytes[i - stride]);
}

// Zigzag of a difference modulo 2^bits: small differences of either sign become small codes.
std::uint32_t zigzag(std::uint32_t difference, std::uint32_t bits) {
  const std::uint32_t modulus = 1u << bits;
  return difference < modulus / 2 ? 2 * difference : 2 * (modulus - difference) - 1;
}
std::uint32_t unzigzag(std::uint32_t code, std::uint32_t bits) {
  const std::uint32_t modulus = 1u << bits;
  return (code % 2 == 0 ? code / 2 : modulus - (code + 1) / 2) & (modulus - 1);
}

std::uint32_t load_value(const std::uint8_t* at, std::uint8_t value_bytes) {
  return value_bytes == 1 ? at[0]
                          : static_cast<std::uint32_t>(at[0]) | static_cast<std::uint32_t>(at[1]) << 8;
}

// In place over bytes [skip, end) of a payload the caller has checked holds them. Both directions walk
// the values in the same order and predict from the same texels: the originals when applying, the
// ones already decoded when undoing.
template <typename Value>
void raster_filter(std::span<std::uint8_t> bytes, const RasterLayout& layout, FilterDirection direction) {
  constexpr std::uint32_t bits = 8 * sizeof(Value);
  constexpr std::uint32_t mask = (1u << bits) - 1;
  const bool apply = direction == FilterDirection::apply;
  const std::size_t count = layout.values();
  const std::size_t texels = std::size_t{layout.width} * layout.height;
  std::uint8_t* const values_at = bytes.data() + layout.skip;  // values, interleaved little-endian
  std::uint8_t* const planes_at = values_at;                   // residual codes, one byte plane after another
  std::vector<Value> values(count);
  if (apply) {
    for (std::size_t i = 0; i < count; ++i)
      values[i] = static_cast<Value>(load_value(values_at + i * sizeof(Value), sizeof(Value)));
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t in_raster = i % texels;
    const auto x = static_cast<std::uint32_t>(in_raster % layout.width);
    const auto y = static_cast<std::uint32_t>(in_raster / layout.width);
    const std::uint32_t prediction = raster_prediction(values.data() + (i - in_raster), layout.width, x, y);
    if (apply) {
      const std::uint32_t code = zigzag((values[i] - prediction) & mask, bits);
      for (std::size_t k = 0; k < sizeof(Value); ++k)
        planes_at[k * count + i] = static_cast<std::uint8_t>(code >> (8 * k));
    } else {
      std::uint32_t code = 0;
      for (std::size_t k = 0; k < sizeof(Value); ++k)
        code |= static_cast<std::uint32_t>(planes_at[k * count + i]) << (8 * k);
      values[i] = static_cast<Value>((prediction + unzigzag(code, bits)) & mask);
    }
  }
  if (!apply) {
    for (std::size_t i = 0; i < count; ++i) {
      for (std::size_t k = 0; k < sizeof(Value); ++k)
        values_at[i * sizeof(Value) + k] = static_cast<std::uint8_t>(values[i] >> (8 * k));
    }
  }
}

}  // namespace

void run_filter(std::vector<std::uint8_t>& bytes, std::uint8_t filter, const RasterLayout& layout,
                FilterDirection direction) {
  const auto sub = [direction](std::span<std::uint8_t> span, std::size_t stride) {
    if (direction == FilterDirection::apply)
      apply_sub_filter(span, stride);
    else
      undo_sub_filter(span, stride);
  };
  if (filter != kRasterFilter) {
    sub(bytes, filter);
    return;
  }
  if (layout.value_bytes == 1)
    raster_filter<std::uint8_t>(bytes, layout, direction);
  else
    raster_filter<std::uint16_t>(bytes, layout, direction);
  sub(std::span(bytes).subspan(static_cast<std::size_t>(layout.end())), layout.rest_stride);
}

RasterLayout source_layout(const RasterLayout& rasters, const RasterWindows& windows) {
  return {rasters.skip,       rasters.value_bytes, windows.source_width, windows.source_height, 1,
          rasters.rest_stride};
}

namespace {

std::vector<std::uint32_t> load_raster_values(std::span<const std::uint8_t> payload,
                                              const RasterLayout& layout) {
  std::vector<std::uint32_t> values(static_cast<std::size_t>(layout.values()));
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = load_value(payload.data() + layout.skip + i * layout.value_bytes, layout.value_bytes);
  return values;
}

void store_value(std::vector<std::uint8_t>& out, std::uint32_t value, std::uint8_t value_bytes) {
  for (std::uint8_t k = 0; k < value_bytes; ++k) out.push_back(static_cast<std::uint8_t>(value >> (8 * k)));
}

}  // namespace

std::optional<std::pair<RasterWindows, std::vector<std::uint8_t>>> window_filtered(
    std::span<const std::uint8_t> payload, const RasterLayout& layout) {
  const std::vector<std::uint32_t> values = load_raster_values(payload, layout);
  std::optional<RasterWindows> windows =
      find_raster_windows(values, layout.width, layout.height, layout.rasters);
  if (!windows) return std::nullopt;
  std::vector<std::uint8_t> stream(payload.begin(), payload.begin() + layout.skip);
  for (std::uint32_t v : compose_window_source(values, layout.width, layout.height, *windows))
    store_value(stream, v, layout.value_bytes);
  stream.insert(stream.end(), payload.begin() + static_cast<std::ptrdiff_t>(layout.end()), payload.end());
  run_filter(stream, kRasterFilter, source_layout(layout, *windows), FilterDirection::apply);
  return std::make_pair(std::move(*windows), std::move(stream));
}

std::vector<std::uint8_t> expand_windows(const std::vector<std::uint8_t>& stream, const RasterLayout& layout,
                                         const RasterWindows& windows, std::uint32_t size) {
  std::vector<std::uint8_t> out(stream.begin(), stream.begin() + layout.skip);
  out.reserve(size);
  const std::size_t row_bytes = std::size_t{layout.width} * layout.value_bytes;
  const std::uint8_t* source = stream.data() + layout.skip;
  for (std::uint32_t i = 0; i < layout.rasters; ++i) {
    for (std::uint32_t y = 0; y < layout.height; ++y) {
      const std::uint8_t* row =
          source +
          ((std::size_t{windows.rows[i]} + y) * windows.source_width + windows.cols[i]) * layout.value_bytes;
      out.insert(out.end(), row, row + row_bytes);
    }
  }
  out.insert(out.end(), source + windows.source_texels() * layout.value_bytes, stream.data() + stream.size());
  return out;
}

}  // namespace carbtf::detail
