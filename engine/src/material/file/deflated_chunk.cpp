#include "material/file/deflated_chunk.hpp"

#include "material/byte_stream.hpp"

namespace carbtf::detail {
namespace {

constexpr std::uint32_t kMaxInflatedBytes = 64u << 20;  // far above any valid chunk (material.hpp limits)

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
bool read_windows(ByteReader& r, const RasterLayout& layout, RasterWindows& windows, std::string& problem) {
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

}  // namespace

Deflater::Deflater() {
  ready_ = deflateInit(&stream_, Z_BEST_COMPRESSION) == Z_OK;
}

Deflater::~Deflater() {
  if (ready_) deflateEnd(&stream_);
}

bool Deflater::pack(std::span<const std::uint8_t> bytes, std::vector<std::uint8_t>& out) {
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
    RasterWindows windows;
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
  RasterWindows windows;
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

}  // namespace carbtf::detail
