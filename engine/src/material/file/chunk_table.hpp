// The material file's chunks, in the order the writer writes them: one row each (chunk_codec.hpp).
#pragma once

#include <span>

#include "material/file/chunk_codec.hpp"

namespace carbtf::detail {

std::span<const ChunkCodec* const> material_chunks();

// The row of `tag`, or -1 for a tag this carbtf does not know (a chunk of a newer minor version).
int material_chunk_number(std::span<const std::uint8_t> tag);

}  // namespace carbtf::detail
