#include "carbtf/engine/material/material_file.hpp"

#include "carbtf/engine/file_output.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string_view>

#include <zlib.h>

#include "material/byte_stream.hpp"
#include "material/raster_prediction.hpp"
#include "material/raster_windows.hpp"

namespace carbtf {
namespace {

using detail::ByteReader;
using detail::ByteWriter;

constexpr std::array<std::uint8_t, 4> kMagic{'C', 'B', 'T', 'F'};
constexpr std::uint32_t kMaxChunks = 64;
constexpr std::size_t kChunkOverhead = 12;  // tag, size, CRC

enum class Chunk {
  settings,
  directions,
  index,
  subspaces,
  range,
  tone,
  tone_weights,
  tone_chroma,
  feather,
  shadows,
  pair_gains,
  specular,
  count
};
constexpr std::array<std::string_view, static_cast<std::size_t>(Chunk::count)> kChunkTags{
    "SETT", "DIRS", "INDX", "SUBS", "RNGE", "TONE", "TWGT", "TCHR", "FTHR", "SHDW", "PGAN", "SPEC"};

// A deflated chunk (format 1.1): payload = inner tag (4 bytes), u32 inner payload size, u8 filter, the
// filter's parameters, then one zlib stream of the filtered payload. Filters:
//   0         none;
//   1..8      Sub with that stride: each byte stored minus the byte `stride` before it, as PNG's Sub
//             filter, which turns smooth u16 and u8 rasters into small repeated values (no parameters);
//   9 (1.3)   raster: u32 skip, u8 value bytes (1 or 2, little-endian), u32 width, u32 height, u32
//             rasters, u8 rest stride. The payload's first `skip` bytes are stored as they are; the
//             `rasters` row-major rasters after them are stored as each value minus its prediction
//             (raster_prediction.hpp), modulo 2^(8 value bytes), zigzag-mapped (0, -1, 1, -2, ... to 0,
//             1, 2, 3, ...), low bytes of every value first, then high bytes; the bytes after the
//             rasters take the Sub filter of `rest stride` (0..8).
//   10 (1.5)  windows: the raster filter's parameters, then u32 source width, u32 source height, and
//             per raster u32 column, u32 row: each raster is the window of one source raster at that
//             texel (raster_windows.hpp), so texels several rasters share are stored once. The stream
//             holds the `skip` bytes, the source raster under the raster filter (one raster of the
//             source's size), then the bytes after the rasters under their Sub filter; the source has at
//             most the rasters' texels.
constexpr std::string_view kDeflatedTag = "DEFL";
constexpr std::uint32_t kMaxInflatedBytes = 64u << 20;  // far above any valid chunk (material.hpp limits)
constexpr std::uint8_t kMaxFilterStride = 8;
constexpr std::uint8_t kRasterFilter = 9;
constexpr std::uint8_t kWindowFilter = 10;

struct RasterLayout {
  std::uint32_t skip = 0;
  std::uint8_t value_bytes = 1;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t rasters = 0;
  std::uint8_t rest_stride = 0;
  std::uint64_t values() const { return std::uint64_t{width} * height * rasters; }
  std::uint64_t end() const { return skip + values() * value_bytes; }
  // Whether the layout is well formed and its rasters lie within `size` bytes (without overflow).
  bool fits(std::uint64_t size) const {
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
};

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

enum class FilterDirection { apply, undo };

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
    const std::uint32_t prediction =
        detail::raster_prediction(values.data() + (i - in_raster), layout.width, x, y);
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

// The layout of the window filter's stream: the source as one raster between the same bytes.
RasterLayout source_layout(const RasterLayout& rasters, const detail::RasterWindows& windows) {
  return {rasters.skip,       rasters.value_bytes, windows.source_width, windows.source_height, 1,
          rasters.rest_stride};
}

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

// The window filter's stream before deflate, or nullopt where the rasters share no texels.
std::optional<std::pair<detail::RasterWindows, std::vector<std::uint8_t>>> window_filtered(
    std::span<const std::uint8_t> payload, const RasterLayout& layout) {
  const std::vector<std::uint32_t> values = load_raster_values(payload, layout);
  std::optional<detail::RasterWindows> windows =
      detail::find_raster_windows(values, layout.width, layout.height, layout.rasters);
  if (!windows) return std::nullopt;
  std::vector<std::uint8_t> stream(payload.begin(), payload.begin() + layout.skip);
  for (std::uint32_t v : detail::compose_window_source(values, layout.width, layout.height, *windows))
    store_value(stream, v, layout.value_bytes);
  stream.insert(stream.end(), payload.begin() + static_cast<std::ptrdiff_t>(layout.end()), payload.end());
  run_filter(stream, kRasterFilter, source_layout(layout, *windows), FilterDirection::apply);
  return std::make_pair(std::move(*windows), std::move(stream));
}

// The smallest of the filtered deflations of `payload`, or empty when none is smaller than it. `rasters`
// (optional) is where the payload holds rasters, for the raster and window filters.
// One zlib deflate stream, reset for each payload: a material's chunks and filters are many small
// payloads, and a fresh stream per payload costs more in allocation than in compression.
class Deflater {
 public:
  Deflater() { ready_ = deflateInit(&stream_, Z_BEST_COMPRESSION) == Z_OK; }
  ~Deflater() {
    if (ready_) deflateEnd(&stream_);
  }
  Deflater(const Deflater&) = delete;
  Deflater& operator=(const Deflater&) = delete;

  // `bytes` as one zlib stream into `out`; false if zlib fails.
  bool pack(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out) {
    if (!ready_ || deflateReset(&stream_) != Z_OK) return false;
    out.resize(deflateBound(&stream_, static_cast<uLong>(bytes.size())));
    stream_.next_in = const_cast<Bytef*>(bytes.data());  // zlib's API is not const; it only reads the input
    stream_.avail_in = static_cast<uInt>(bytes.size());
    stream_.next_out = out.data();
    stream_.avail_out = static_cast<uInt>(out.size());
    if (deflate(&stream_, Z_FINISH) != Z_STREAM_END) return false;
    out.resize(out.size() - stream_.avail_out);
    return true;
  }

 private:
  z_stream stream_{};
  bool ready_ = false;
};

std::vector<std::uint8_t> deflate_chunk(Deflater& deflater, std::string_view tag,
                                        std::span<const std::uint8_t> payload,
                                        const std::optional<RasterLayout>& rasters) {
  std::vector<std::uint8_t> best;
  const bool has_rasters = rasters && rasters->fits(payload.size());
  std::vector<std::uint8_t> filters{0, 1, 2};
  if (has_rasters) filters.insert(filters.end(), {kRasterFilter, kWindowFilter});
  for (std::uint8_t filter : filters) {
    const RasterLayout layout = filter >= kRasterFilter ? *rasters : RasterLayout{};
    std::vector<std::uint8_t> filtered;
    detail::RasterWindows windows;
    if (filter == kWindowFilter) {
      auto windowed = window_filtered(payload, layout);
      if (!windowed) continue;
      windows = std::move(windowed->first);
      filtered = std::move(windowed->second);
    } else {
      filtered.assign(payload.begin(), payload.end());
      run_filter(filtered, filter, layout, FilterDirection::apply);
    }
    std::vector<std::uint8_t> packed;
    if (!deflater.pack(filtered, packed)) continue;
    std::vector<std::uint8_t> chunk;
    ByteWriter w(chunk);
    w.bytes(std::span(reinterpret_cast<const std::uint8_t*>(tag.data()), 4));
    w.u32(static_cast<std::uint32_t>(payload.size()));
    w.u8(filter);
    if (filter >= kRasterFilter) {
      w.u32(layout.skip);
      w.u8(layout.value_bytes);
      w.u32(layout.width);
      w.u32(layout.height);
      w.u32(layout.rasters);
      w.u8(layout.rest_stride);
    }
    if (filter == kWindowFilter) {
      w.u32(windows.source_width);
      w.u32(windows.source_height);
      for (std::size_t r = 0; r < windows.rows.size(); ++r) {
        w.u32(windows.cols[r]);
        w.u32(windows.rows[r]);
      }
    }
    w.bytes(packed);
    if (chunk.size() < payload.size() && (best.empty() || chunk.size() < best.size()))
      best = std::move(chunk);
  }
  return best;
}

// Inflates one zlib stream that must give exactly `size` bytes. It grows the output as the stream
// produces it, so a chunk that lies about its size costs what its stream holds, not what it claims.
bool inflate_exactly(std::span<const std::uint8_t> packed, std::uint32_t size, std::vector<std::uint8_t>& out,
                     std::string& problem) {
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) {
    problem = "could not start zlib";
    return false;
  }
  stream.next_in = const_cast<Bytef*>(packed.data());  // zlib's API is not const; it only reads the input
  stream.avail_in = static_cast<uInt>(packed.size());
  out.clear();
  std::array<std::uint8_t, 16384> buffer{};
  int result = Z_OK;
  bool too_long = false;
  while (result == Z_OK) {
    stream.next_out = buffer.data();
    stream.avail_out = static_cast<uInt>(buffer.size());
    result = inflate(&stream, Z_NO_FLUSH);
    const std::size_t produced = buffer.size() - stream.avail_out;
    if (out.size() + produced > size) {
      too_long = true;
      break;
    }
    out.insert(out.end(), buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(produced));
  }
  inflateEnd(&stream);
  if (too_long || result != Z_STREAM_END || out.size() != size) {
    const std::string zlib = too_long                                          ? "long"
                             : result == Z_STREAM_END || result == Z_BUF_ERROR ? "short"
                                                                               : std::to_string(result);
    problem = "does not inflate to its " + std::to_string(size) + " bytes (zlib: " + zlib + ")";
    return false;
  }
  return true;
}

// The window filter's placement, checked: every window inside the source, and the source no larger
// than the rasters it replaces (so the stream is no longer than the payload).
bool read_windows(ByteReader& r, const RasterLayout& layout, detail::RasterWindows& windows,
                  std::string& problem) {
  windows.source_width = r.u32();
  windows.source_height = r.u32();
  if (r.failed() || !r.can_read(layout.rasters, 8)) {
    problem = "is truncated in its window placement";
    return false;
  }
  windows.cols.resize(layout.rasters);
  windows.rows.resize(layout.rasters);
  bool inside = true;
  for (std::uint32_t i = 0; i < layout.rasters; ++i) {
    windows.cols[i] = r.u32();
    windows.rows[i] = r.u32();
    inside = inside && std::uint64_t{windows.cols[i]} + layout.width <= windows.source_width &&
             std::uint64_t{windows.rows[i]} + layout.height <= windows.source_height;
  }
  if (!inside || windows.source_texels() > layout.values()) {
    problem = "has a window placement outside its " + std::to_string(windows.source_width) + " x " +
              std::to_string(windows.source_height) + " source, or a source larger than its rasters";
    return false;
  }
  return true;
}

// The payload from the window filter's unfiltered stream (the skip bytes, the source values, the rest).
std::vector<std::uint8_t> expand_windows(const std::vector<std::uint8_t>& stream, const RasterLayout& layout,
                                         const detail::RasterWindows& windows, std::uint32_t size) {
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

// Inflates a DEFL payload into its inner tag and payload; false with `problem` set when it is malformed.
bool inflate_chunk(std::span<const std::uint8_t> payload, std::array<std::uint8_t, 4>& tag,
                   std::vector<std::uint8_t>& out, std::string& problem) {
  ByteReader r(payload);
  const auto inner = r.bytes(4);
  const std::uint32_t size = r.u32();
  const std::uint8_t filter = r.u8();
  RasterLayout layout;
  if (filter == kRasterFilter || filter == kWindowFilter) {
    layout.skip = r.u32();
    layout.value_bytes = r.u8();
    layout.width = r.u32();
    layout.height = r.u32();
    layout.rasters = r.u32();
    layout.rest_stride = r.u8();
  }
  if (r.failed()) {
    problem = "is truncated";
    return false;
  }
  std::copy(inner.begin(), inner.end(), tag.begin());
  if (filter > kMaxFilterStride && filter != kRasterFilter && filter != kWindowFilter) {
    problem = "has unknown filter " + std::to_string(filter) + " (this carbtf knows 0-" +
              std::to_string(kWindowFilter) + ")";
    return false;
  }
  if (filter >= kRasterFilter && !layout.fits(size)) {
    problem = "has a raster filter that does not fit its " + std::to_string(size) + " bytes (skip " +
              std::to_string(layout.skip) + ", " + std::to_string(layout.value_bytes) + "-byte values, " +
              std::to_string(layout.width) + " x " + std::to_string(layout.height) + " x " +
              std::to_string(layout.rasters) + ", rest stride " + std::to_string(layout.rest_stride) + ")";
    return false;
  }
  detail::RasterWindows windows;
  std::uint64_t stream_size = size;
  if (filter == kWindowFilter) {
    if (!read_windows(r, layout, windows, problem)) return false;
    stream_size = size - (layout.values() - windows.source_texels()) * layout.value_bytes;
  }
  const std::size_t packed = r.remaining();
  // zlib expands at most about 1032:1, so a larger claim is a lie; refusing it bounds the allocation.
  if (size > kMaxInflatedBytes || stream_size > packed * 1100 + 64) {
    problem = "claims " + std::to_string(stream_size) + " inflated bytes from " + std::to_string(packed);
    return false;
  }
  if (!inflate_exactly(r.bytes(packed), static_cast<std::uint32_t>(stream_size), out, problem)) return false;
  if (filter != kWindowFilter) {
    run_filter(out, filter, layout, FilterDirection::undo);
    return true;
  }
  run_filter(out, kRasterFilter, source_layout(layout, windows), FilterDirection::undo);
  out = expand_windows(out, layout, windows, size);
  return true;
}

int chunk_number(std::span<const std::uint8_t> tag) {
  const std::string_view text(reinterpret_cast<const char*>(tag.data()), tag.size());
  for (std::size_t i = 0; i < kChunkTags.size(); ++i) {
    if (kChunkTags[i] == text) return static_cast<int>(i);
  }
  return -1;
}

std::string printable_tag(std::span<const std::uint8_t> tag) {
  std::string text;
  for (std::uint8_t c : tag) text += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  return text;
}

const std::array<std::uint32_t, 256>& crc_table() {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  return table;
}

// ---- encoding ---------------------------------------------------------------------------------------

void encode_settings(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.settings.size()));
  for (const auto& [key, value] : m.settings) {
    w.text(key);
    w.text(value);
  }
}

void encode_directions(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.lights.size()));
  w.u32(static_cast<std::uint32_t>(m.views.size()));
  for (const auto* set : {&m.lights, &m.views}) {
    for (const MaterialDirection& d : *set) {
      w.f32(d.theta);
      w.f32(d.phi);
    }
  }
}

void encode_index(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.lights.size()));
  w.u32(static_cast<std::uint32_t>(m.views.size()));
  w.bytes(m.subspace_index);
}

void encode_subspaces(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.subspaces.size()));
  for (const SubspaceModel& s : m.subspaces) {
    for (std::uint32_t v : {s.light, s.view, s.width, s.height, s.channels, s.levels}) w.u32(v);
    for (float v : s.colour_mean) w.f32(v);
    for (float v : s.colour_transform) w.f32(v);
    for (const CarBandModel& b : s.bands) {
      w.u32(b.flags);
      w.f32(b.mean);
      w.f32(b.band_std);
      w.f32(b.sigma);
      w.u32(static_cast<std::uint32_t>(b.neighbourhood.size()));
      for (CarNeighbour n : b.neighbourhood) {
        w.i8(n.dr);
        w.i8(n.dc);
      }
      for (float g : b.gamma) w.f32(g);
    }
  }
}

constexpr std::uint32_t kRangeHeaderBytes = 16;  // tile size, edge colours, height offset and scale
constexpr std::uint32_t kToneHeaderBytes = 12;   // tone offset and scale, count

void encode_range(const Material& m, ByteWriter& w) {
  const RangeTiles& r = m.range;
  w.u32(r.tile_size);
  w.u32(r.edge_colours);
  w.f32(r.height_offset);
  w.f32(r.height_scale);
  for (std::uint16_t v : r.patches) w.u16(v);
  for (std::uint16_t v : r.cuts) w.u16(v);
}

// Optional (format 1.1): written only when the material has a relief tone.
void encode_tone(const Material& m, ByteWriter& w) {
  const RangeTiles& r = m.range;
  w.f32(r.tone_offset);
  w.f32(r.tone_scale);
  w.u32(static_cast<std::uint32_t>(r.tone.size()));
  w.bytes(r.tone);
}

// Where a chunk's payload holds rasters (the patches of heights or tone), for the raster filter.
std::optional<RasterLayout> chunk_rasters(Chunk chunk, const Material& m) {
  // Three planes of lights x views gains, smooth over both: a raster per colour channel.
  if (chunk == Chunk::pair_gains) {
    return RasterLayout{
        8, 1, static_cast<std::uint32_t>(m.views.size()), static_cast<std::uint32_t>(m.lights.size()), 3, 0};
  }
  const RangeTiles& r = m.range;
  if (r.tile_size == 0) return std::nullopt;
  const std::uint32_t patches = 2 * r.edge_colours;
  // The cuts after the patches are runs of small steps: Sub over u16 turns them into 0s and 1s.
  if (chunk == Chunk::range) return RasterLayout{kRangeHeaderBytes, 2, r.tile_size, r.tile_size, patches, 2};
  if (chunk == Chunk::tone)
    return RasterLayout{kToneHeaderBytes,
                        1,
                        r.tile_size,
                        r.tile_size,
                        patches * static_cast<std::uint32_t>(tone_planes(r)),
                        0};
  return std::nullopt;
}

// ---- decoding: each returns false on a short or out-of-limit payload ---------------------------------

bool decode_settings(ByteReader& r, Material& m) {
  const std::uint32_t count = r.u32();
  if (count > kMaxSettings || !r.can_read(count, 8)) return false;
  m.settings.resize(count);
  for (auto& [key, value] : m.settings) {
    key = r.text(kMaxSettingLength);
    value = r.text(kMaxSettingLength);
  }
  return !r.failed();
}

bool decode_direction_counts(ByteReader& r, std::uint32_t& lights, std::uint32_t& views) {
  lights = r.u32();
  views = r.u32();
  return !r.failed() && lights <= kMaxMaterialDirections && views <= kMaxMaterialDirections;
}

bool decode_directions(ByteReader& r, Material& m) {
  std::uint32_t lights = 0, views = 0;
  if (!decode_direction_counts(r, lights, views) || !r.can_read(std::size_t{lights} + views, 8)) return false;
  m.lights.resize(lights);
  m.views.resize(views);
  for (auto* set : {&m.lights, &m.views}) {
    for (MaterialDirection& d : *set) {
      d.theta = r.f32();
      d.phi = r.f32();
    }
  }
  return !r.failed();
}

bool decode_index(ByteReader& r, Material& m, std::uint32_t& lights, std::uint32_t& views) {
  if (!decode_direction_counts(r, lights, views)) return false;
  const auto table = r.bytes(std::size_t{lights} * views);
  m.subspace_index.assign(table.begin(), table.end());
  return !r.failed();
}

bool decode_band(ByteReader& r, CarBandModel& b) {
  b.flags = r.u32();
  b.mean = r.f32();
  b.band_std = r.f32();
  b.sigma = r.f32();
  const std::uint32_t neighbours = r.u32();
  if (neighbours > kMaxNeighbours || !r.can_read(neighbours, 6)) return false;
  b.neighbourhood.resize(neighbours);
  for (CarNeighbour& n : b.neighbourhood) {
    n.dr = r.i8();
    n.dc = r.i8();
  }
  b.gamma.resize(neighbours);
  for (float& g : b.gamma) g = r.f32();
  return !r.failed();
}

bool decode_subspaces(ByteReader& r, Material& m) {
  const std::uint32_t count = r.u32();
  if (count > kMaxSubspaces || !r.can_read(count, 24)) return false;
  m.subspaces.resize(count);
  for (SubspaceModel& s : m.subspaces) {
    s.light = r.u32();
    s.view = r.u32();
    s.width = r.u32();
    s.height = r.u32();
    s.channels = r.u32();
    s.levels = r.u32();
    if (r.failed() || s.channels == 0 || s.channels > kMaxChannels || s.levels == 0 ||
        s.levels > kMaxPyramidLevels)
      return false;
    const std::size_t floats = s.channels + std::size_t{s.channels} * s.channels;
    const std::size_t bands = std::size_t{s.levels} * s.channels;
    if (!r.can_read(floats + bands * 5, 4)) return false;
    s.colour_mean.resize(s.channels);
    for (float& v : s.colour_mean) v = r.f32();
    s.colour_transform.resize(std::size_t{s.channels} * s.channels);
    for (float& v : s.colour_transform) v = r.f32();
    s.bands.resize(bands);
    for (CarBandModel& b : s.bands) {
      if (!decode_band(r, b)) return false;
    }
  }
  return !r.failed();
}

bool decode_range(ByteReader& r, Material& m) {
  RangeTiles& t = m.range;
  t.tile_size = r.u32();
  t.edge_colours = r.u32();
  t.height_offset = r.f32();
  t.height_scale = r.f32();
  if (r.failed() || t.tile_size > kMaxTileSize || t.edge_colours > kMaxEdgeColours) return false;
  if (t.tile_size == 0) return true;
  const std::size_t c = t.edge_colours;
  const std::size_t patch_values = 2 * c * t.tile_size * t.tile_size;
  const std::size_t cut_values = c * c * c * c * 4 * (t.tile_size / 2);
  if (!r.can_read(patch_values + cut_values, 2)) return false;
  t.patches.resize(patch_values);
  for (auto& v : t.patches) v = r.u16();
  t.cuts.resize(cut_values);
  for (auto& v : t.cuts) v = r.u16();
  return !r.failed();
}

// Optional (format 1.2): written only when a subspace takes less than the whole tone.
bool has_tone_weights(const Material& m) {
  return std::any_of(m.subspaces.begin(), m.subspaces.end(),
                     [](const SubspaceModel& s) { return s.tone_weight != 1.0f; });
}

void encode_tone_weights(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.subspaces.size()));
  for (const SubspaceModel& s : m.subspaces) w.f32(s.tone_weight);
}

// Into `weights`: the subspaces may come later in the file.
bool decode_tone_weights(ByteReader& r, std::vector<float>& weights) {
  const std::uint32_t count = r.u32();
  if (r.failed() || count > kMaxSubspaces || !r.can_read(count, 4)) return false;
  weights.resize(count);
  for (float& w : weights) w = r.f32();
  return !r.failed();
}

// Optional (format 1.4): written only when the tone is not grey.
bool has_tone_chroma(const Material& m) {
  return std::any_of(m.range.tone_chroma.begin(), m.range.tone_chroma.end(),
                     [](float c) { return c != 1.0f; });
}

void encode_tone_chroma(const Material& m, ByteWriter& w) {
  for (float c : m.range.tone_chroma) w.f32(c);
}

// Optional (format 1.6): written only for feathered cuts.
void encode_feather(const Material& m, ByteWriter& w) {
  w.u32(m.range.feather);
}

// Into `feather`: the range chunk may come later in the file.
bool decode_feather(ByteReader& r, std::uint32_t& feather) {
  feather = r.u32();
  return !r.failed();
}

// Optional (format 1.8): written only when the relief casts shadows.
void encode_shadows(const Material& m, ByteWriter& w) {
  w.f32(m.range.shadow_scale);
}

// Into `scale`: the range chunk may come later in the file.
bool decode_shadows(ByteReader& r, float& scale) {
  scale = r.f32();
  return !r.failed();
}

// Optional (format 1.10): written only when the relief has a specular lobe.
void encode_specular(const Material& m, ByteWriter& w) {
  w.f32(m.range.specular_strength);
  w.f32(m.range.specular_gloss);
}

// Into `lobe`: the range chunk may come later in the file.
bool decode_specular(ByteReader& r, std::array<float, 2>& lobe) {
  lobe[0] = r.f32();
  lobe[1] = r.f32();
  return !r.failed();
}

// Optional (format 1.9): written only when the material has pair gains.
void encode_pair_gains(const Material& m, ByteWriter& w) {
  w.u32(static_cast<std::uint32_t>(m.lights.size()));
  w.u32(static_cast<std::uint32_t>(m.views.size()));
  w.bytes(m.pair_gains);
}

// The counts are checked against the directions once every chunk is read (validate_material).
bool decode_pair_gains(ByteReader& r, Material& m) {
  std::uint32_t lights = 0, views = 0;
  if (!decode_direction_counts(r, lights, views)) return false;
  const std::size_t count = 3 * std::size_t{lights} * views;
  if (!r.can_read(count, 1)) return false;
  const auto bytes = r.bytes(count);
  m.pair_gains.assign(bytes.begin(), bytes.end());
  return !r.failed();
}

// Into `chroma`: the range chunk may come later in the file.
bool decode_tone_chroma(ByteReader& r, std::array<float, 3>& chroma) {
  for (float& c : chroma) c = r.f32();
  return !r.failed();
}

bool decode_tone(ByteReader& r, Material& m) {
  RangeTiles& t = m.range;
  t.tone_offset = r.f32();
  t.tone_scale = r.f32();
  const std::uint32_t count = r.u32();
  constexpr std::size_t kMaxToneTexels =
      3 * 2 * std::size_t{kMaxEdgeColours} * kMaxTileSize * kMaxTileSize;  // three planes
  if (r.failed() || count > kMaxToneTexels || !r.can_read(count, 1)) return false;
  const auto bytes = r.bytes(count);
  t.tone.assign(bytes.begin(), bytes.end());
  return !r.failed();
}

Status fail(const std::string& name, const std::string& problem) {
  return {ErrorCode::invalid_material, name + ": " + problem};
}

// Walks the header and chunk table, checking sizes and CRCs; calls visit(tag, payload) per chunk.
template <typename Visit>
Status walk_chunks(std::span<const std::uint8_t> bytes, const std::string& name, Visit&& visit) {
  ByteReader r(bytes);
  const auto magic = r.bytes(4);
  if (r.failed() || !std::equal(magic.begin(), magic.end(), kMagic.begin())) {
    return fail(name, bytes.size() < 4 ? "too short to be a carbtf material file"
                                       : "not a carbtf material file (no CBTF signature)");
  }
  const std::uint16_t major = r.u16();
  const std::uint16_t minor = r.u16();
  const std::uint32_t chunks = r.u32();
  if (r.failed()) return fail(name, "truncated header");
  if (major != kMaterialFormatMajor) {
    return fail(name, "material format " + std::to_string(major) + "." + std::to_string(minor) +
                          " is not supported (this carbtf reads " + std::to_string(kMaterialFormatMajor) +
                          ".x)");
  }
  if (chunks > kMaxChunks)
    return fail(name,
                "claims " + std::to_string(chunks) + " chunks (at most " + std::to_string(kMaxChunks) + ")");
  for (std::uint32_t i = 0; i < chunks; ++i) {
    const auto tag = r.bytes(4);
    const std::uint32_t size = r.u32();
    if (r.failed()) return fail(name, "truncated in the header of chunk " + std::to_string(i));
    if (size > r.remaining() || r.remaining() - size < 4) {
      return fail(name, "chunk " + printable_tag(tag) + " claims " + std::to_string(size) +
                            " bytes but the file is truncated");
    }
    const auto payload = r.bytes(size);
    const std::uint32_t stored_crc = r.u32();
    std::uint32_t crc = crc32(tag);
    std::array<std::uint8_t, 4> size_bytes{};
    for (int k = 0; k < 4; ++k) size_bytes[k] = static_cast<std::uint8_t>(size >> (8 * k));
    crc = crc32(size_bytes, crc);
    crc = crc32(payload, crc);
    if (crc != stored_crc) return fail(name, "chunk " + printable_tag(tag) + " is corrupt (CRC mismatch)");
    if (Status s = visit(tag, payload); !s.ok()) return s;
  }
  if (!r.at_end())
    return fail(name, std::to_string(r.remaining()) + " unexpected bytes after the last chunk");
  return {};
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  const auto& table = crc_table();
  crc = ~crc;
  for (std::uint8_t b : bytes) crc = table[(crc ^ b) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

Status encode_material(const Material& material, std::vector<std::uint8_t>& out,
                       const MaterialEncoding& encoding) {
  if (Status s = validate_material(material); !s.ok())
    return {ErrorCode::invalid_argument, "cannot encode material: " + s.message()};
  out.clear();
  ByteWriter w(out);
  w.bytes(kMagic);
  w.u16(kMaterialFormatMajor);
  w.u16(kMaterialFormatMinor);
  std::array<bool, static_cast<std::size_t>(Chunk::count)> written{};
  written.fill(true);
  written[static_cast<std::size_t>(Chunk::tone)] = !material.range.tone.empty();
  written[static_cast<std::size_t>(Chunk::tone_weights)] = has_tone_weights(material);
  written[static_cast<std::size_t>(Chunk::tone_chroma)] = has_tone_chroma(material);
  written[static_cast<std::size_t>(Chunk::feather)] = material.range.feather > 0;
  written[static_cast<std::size_t>(Chunk::shadows)] = material.range.shadow_scale > 0.0f;
  written[static_cast<std::size_t>(Chunk::pair_gains)] = !material.pair_gains.empty();
  written[static_cast<std::size_t>(Chunk::specular)] = material.range.specular_strength > 0.0f;
  w.u32(static_cast<std::uint32_t>(std::count(written.begin(), written.end(), true)));
  Deflater deflater;
  using Encoder = void (*)(const Material&, ByteWriter&);
  constexpr std::array<Encoder, static_cast<std::size_t>(Chunk::count)> encoders{
      encode_settings, encode_directions, encode_index,        encode_subspaces,
      encode_range,    encode_tone,       encode_tone_weights, encode_tone_chroma,
      encode_feather,  encode_shadows,    encode_pair_gains,   encode_specular};
  for (std::size_t c = 0; c < encoders.size(); ++c) {
    if (!written[c]) continue;
    std::vector<std::uint8_t> payload;
    ByteWriter payload_writer(payload);
    encoders[c](material, payload_writer);
    // Settings stay plain text, readable with a hex viewer; the rest is deflated where that is smaller.
    std::vector<std::uint8_t> deflated;
    if (encoding.deflate && static_cast<Chunk>(c) != Chunk::settings)
      deflated =
          deflate_chunk(deflater, kChunkTags[c], payload, chunk_rasters(static_cast<Chunk>(c), material));
    const std::string_view tag = deflated.empty() ? kChunkTags[c] : kDeflatedTag;
    const std::vector<std::uint8_t>& body = deflated.empty() ? payload : deflated;
    const std::size_t start = w.size();
    w.bytes(std::span(reinterpret_cast<const std::uint8_t*>(tag.data()), 4));
    w.u32(static_cast<std::uint32_t>(body.size()));
    w.bytes(body);
    w.u32(crc32(std::span(out).subspan(start, 8 + body.size())));
  }
  return {};
}

Status decode_material(std::span<const std::uint8_t> bytes, const std::string& name, Material& out) {
  Material m;
  std::array<bool, static_cast<std::size_t>(Chunk::count)> seen{};
  std::uint32_t index_lights = 0, index_views = 0;
  std::vector<float> tone_weights;
  std::array<float, 3> tone_chroma{1.0f, 1.0f, 1.0f};
  std::uint32_t feather = 0;
  float shadow_scale = 0.0f;
  std::array<float, 2> specular{0.0f, 0.0f};
  Status walked = walk_chunks(
      bytes, name,
      [&](std::span<const std::uint8_t> outer_tag, std::span<const std::uint8_t> outer_payload) -> Status {
        std::span<const std::uint8_t> tag = outer_tag;
        std::span<const std::uint8_t> payload = outer_payload;
        std::array<std::uint8_t, 4> inner_tag{};
        std::vector<std::uint8_t> inflated;
        if (printable_tag(outer_tag) == kDeflatedTag) {
          std::string problem;
          if (!inflate_chunk(outer_payload, inner_tag, inflated, problem))
            return fail(name, "deflated chunk " + problem);
          if (printable_tag(inner_tag) == kDeflatedTag)
            return fail(name, "a deflated chunk holds another deflated chunk");
          tag = inner_tag;
          payload = inflated;
        }
        const int number = chunk_number(tag);
        if (number < 0) return {};  // a chunk from a newer minor version
        if (seen[number]) return fail(name, "chunk " + printable_tag(tag) + " appears twice");
        seen[number] = true;
        ByteReader r(payload);
        bool ok = false;
        switch (static_cast<Chunk>(number)) {
          case Chunk::settings:
            ok = decode_settings(r, m);
            break;
          case Chunk::directions:
            ok = decode_directions(r, m);
            break;
          case Chunk::index:
            ok = decode_index(r, m, index_lights, index_views);
            break;
          case Chunk::subspaces:
            ok = decode_subspaces(r, m);
            break;
          case Chunk::range:
            ok = decode_range(r, m);
            break;
          case Chunk::tone:
            ok = decode_tone(r, m);
            break;
          case Chunk::tone_weights:
            ok = decode_tone_weights(r, tone_weights);
            break;
          case Chunk::tone_chroma:
            ok = decode_tone_chroma(r, tone_chroma);
            break;
          case Chunk::feather:
            ok = decode_feather(r, feather);
            break;
          case Chunk::shadows:
            ok = decode_shadows(r, shadow_scale);
            break;
          case Chunk::pair_gains:
            ok = decode_pair_gains(r, m);
            break;
          case Chunk::specular:
            ok = decode_specular(r, specular);
            break;
          case Chunk::count:
            break;
        }
        if (!ok)
          return fail(name, "chunk " + printable_tag(tag) + " is truncated or has out-of-range counts");
        if (!r.at_end())
          return fail(name, "chunk " + printable_tag(tag) + " has " + std::to_string(r.remaining()) +
                                " trailing bytes");
        return {};
      });
  if (!walked.ok()) return walked;
  for (std::size_t c = 0; c < seen.size(); ++c) {
    const bool optional =
        static_cast<Chunk>(c) == Chunk::settings || static_cast<Chunk>(c) == Chunk::tone ||
        static_cast<Chunk>(c) == Chunk::tone_weights || static_cast<Chunk>(c) == Chunk::tone_chroma ||
        static_cast<Chunk>(c) == Chunk::feather || static_cast<Chunk>(c) == Chunk::shadows ||
        static_cast<Chunk>(c) == Chunk::pair_gains || static_cast<Chunk>(c) == Chunk::specular;
    if (!seen[c] && !optional) return fail(name, "chunk " + std::string(kChunkTags[c]) + " is missing");
  }
  if (index_lights != m.lights.size() || index_views != m.views.size()) {
    return fail(name, "the index table is " + std::to_string(index_lights) + " x " +
                          std::to_string(index_views) + " but there are " + std::to_string(m.lights.size()) +
                          " lights and " + std::to_string(m.views.size()) + " views");
  }
  if (seen[static_cast<std::size_t>(Chunk::tone_weights)]) {
    if (tone_weights.size() != m.subspaces.size()) {
      return fail(name, "chunk TWGT has " + std::to_string(tone_weights.size()) + " tone weights for " +
                            std::to_string(m.subspaces.size()) + " subspaces");
    }
    for (std::size_t s = 0; s < tone_weights.size(); ++s) m.subspaces[s].tone_weight = tone_weights[s];
  }
  m.range.tone_chroma = tone_chroma;
  m.range.feather = feather;
  m.range.shadow_scale = shadow_scale;
  m.range.specular_strength = specular[0];
  m.range.specular_gloss = specular[1];
  if (Status s = validate_material(m); !s.ok()) return fail(name, s.message());
  out = std::move(m);
  return {};
}

Status list_material_chunks(std::span<const std::uint8_t> bytes, std::vector<MaterialChunkInfo>& out) {
  out.clear();
  return walk_chunks(
      bytes, "material",
      [&](std::span<const std::uint8_t> tag, std::span<const std::uint8_t> payload) -> Status {
        if (printable_tag(tag) == kDeflatedTag && payload.size() >= 9) {
          const std::uint32_t inflated =
              static_cast<std::uint32_t>(payload[4]) | static_cast<std::uint32_t>(payload[5]) << 8 |
              static_cast<std::uint32_t>(payload[6]) << 16 | static_cast<std::uint32_t>(payload[7]) << 24;
          out.push_back({printable_tag(payload.first(4)), payload.size() + kChunkOverhead,
                         chunk_number(payload.first(4)) >= 0, inflated + kChunkOverhead});
          return {};
        }
        out.push_back({printable_tag(tag), payload.size() + kChunkOverhead, chunk_number(tag) >= 0, 0});
        return {};
      });
}

Status read_material_file_bytes(const std::string& path, std::vector<std::uint8_t>& bytes) {
  // A folder, FIFO or device is refused before it is opened: opening a FIFO would wait for a writer.
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status))
    return {ErrorCode::file_error, path + ": no such material file"};
  if (std::filesystem::is_directory(status))
    return {ErrorCode::file_error, path + ": is a folder, not a material file (.cbtf)"};
  if (!std::filesystem::is_regular_file(status))
    return {ErrorCode::file_error,
            path + ": is not a regular file (a pipe or device?), so it is not read as a material"};
  std::ifstream file(path, std::ios::binary);
  if (!file) return {ErrorCode::file_error, path + ": cannot open the material file"};
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  // A valid material is far below this; refusing early keeps a mistaken path (a BTF zip) cheap.
  constexpr std::streamoff kMaxFileBytes = std::streamoff{256} << 20;
  if (size < 0) return {ErrorCode::file_error, path + ": cannot read the material file"};
  if (size > kMaxFileBytes)
    return fail(path, "is " + std::to_string(size >> 20) + " MiB, too large to be a carbtf material file");
  file.seekg(0);
  bytes.resize(static_cast<std::size_t>(size));
  if (!file.read(reinterpret_cast<char*>(bytes.data()), size))
    return {ErrorCode::file_error, path + ": cannot read the material file"};
  return {};
}

Status read_material_file(const std::string& path, Material& out) {
  std::vector<std::uint8_t> bytes;
  if (Status s = read_material_file_bytes(path, bytes); !s.ok()) return s;
  return decode_material(bytes, path, out);
}

Status write_material_file(const std::string& path, const Material& material) {
  // Refused before the encoding's work, as a command refuses it before the analysis.
  if (Status s = check_output_file(path); !s.ok()) return s;
  std::vector<std::uint8_t> bytes;
  if (Status s = encode_material(material, bytes); !s.ok()) return s;
  return write_file_whole(path, bytes);
}

}  // namespace carbtf
