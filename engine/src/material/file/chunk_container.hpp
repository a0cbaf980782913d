// The material file's container, whatever its chunks hold: the header ("CBTF", u16 major, u16 minor,
// u32 chunk count), then per chunk a 4-byte tag, u32 payload size, the payload and a CRC-32 of tag, size
// and payload. Nothing here knows a chunk's meaning (chunk_table.hpp does).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "carbtf/engine/status.hpp"

namespace carbtf::detail {

inline constexpr std::array<std::uint8_t, 4> kMaterialMagic{'C', 'B', 'T', 'F'};
inline constexpr std::uint32_t kMaxChunks = 64;
inline constexpr std::size_t kChunkOverhead = 12;  // tag, size, CRC

// An invalid_material error: "`name`: `problem`".
Status material_error(const std::string& name, const std::string& problem);

// The tag as text, with '?' for bytes that are not printable ASCII (for error messages).
std::string printable_tag(std::span<const std::uint8_t> tag);

// The header, with the chunk count to follow.
void write_container_header(std::vector<std::uint8_t>& out, std::uint32_t chunks);

// One chunk appended to `out`: tag, size, body and CRC.
void write_chunk(std::vector<std::uint8_t>& out, std::string_view tag, std::span<const std::uint8_t> body);

using ChunkVisitor =
    std::function<Status(std::span<const std::uint8_t> tag, std::span<const std::uint8_t> payload)>;

// Walks the header and chunks, checking the signature, the major version, sizes and CRCs; calls `visit`
// per chunk and stops at its first error. `name` prefixes every message.
Status walk_chunks(std::span<const std::uint8_t> bytes, const std::string& name, const ChunkVisitor& visit);

}  // namespace carbtf::detail
