#include "material/file/chunk_container.hpp"

#include <algorithm>

#include "carbtf/engine/material/material_file.hpp"
#include "material/byte_stream.hpp"

namespace carbtf {
namespace {

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

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  const auto& table = crc_table();
  crc = ~crc;
  for (std::uint8_t b : bytes) crc = table[(crc ^ b) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

namespace detail {

Status material_error(const std::string& name, const std::string& problem) {
  return {ErrorCode::invalid_material, name + ": " + problem};
}

std::string printable_tag(std::span<const std::uint8_t> tag) {
  std::string text;
  for (std::uint8_t c : tag) text += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  return text;
}

void write_container_header(std::vector<std::uint8_t>& out, std::uint32_t chunks) {
  ByteWriter w(out);
  w.bytes(kMaterialMagic);
  w.u16(kMaterialFormatMajor);
  w.u16(kMaterialFormatMinor);
  w.u32(chunks);
}

void write_chunk(std::vector<std::uint8_t>& out, std::string_view tag, std::span<const std::uint8_t> body) {
  ByteWriter w(out);
  const std::size_t start = w.size();
  w.bytes(std::span(reinterpret_cast<const std::uint8_t*>(tag.data()), 4));
  w.u32(static_cast<std::uint32_t>(body.size()));
  w.bytes(body);
  w.u32(crc32(std::span(out).subspan(start, 8 + body.size())));
}

Status walk_chunks(std::span<const std::uint8_t> bytes, const std::string& name, const ChunkVisitor& visit) {
  const auto fail = material_error;
  ByteReader r(bytes);
  const auto magic = r.bytes(4);
  if (r.failed() || !std::equal(magic.begin(), magic.end(), kMaterialMagic.begin())) {
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

}  // namespace detail
}  // namespace carbtf
