#include "carbtf/engine/material/material_file.hpp"

#include "carbtf/engine/file_output.hpp"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <string_view>

#include "material/file/chunk_container.hpp"
#include "material/file/chunk_table.hpp"
#include "material/file/deflated_chunk.hpp"

namespace carbtf {

using detail::ByteReader;
using detail::ByteWriter;
using detail::ChunkCodec;
using detail::material_chunk_number;
using detail::material_chunks;
using detail::printable_tag;

Status encode_material(const Material& material, std::vector<std::uint8_t>& out,
                       const MaterialEncoding& encoding) {
  if (Status s = validate_material(material); !s.ok())
    return {ErrorCode::invalid_argument, "cannot encode material: " + s.message()};
  const auto written = [&material](const ChunkCodec* chunk) {
    return chunk->present == nullptr || chunk->present(material);
  };
  out.clear();
  detail::write_container_header(out, static_cast<std::uint32_t>(std::count_if(
                                          material_chunks().begin(), material_chunks().end(), written)));
  detail::Deflater deflater;
  for (const ChunkCodec* chunk : material_chunks()) {
    if (!written(chunk)) continue;
    std::vector<std::uint8_t> payload;
    ByteWriter payload_writer(payload);
    chunk->encode(material, payload_writer);
    // Deflated where that is smaller.
    std::vector<std::uint8_t> deflated;
    if (encoding.deflate && chunk->deflatable) {
      const auto rasters = chunk->rasters ? chunk->rasters(material) : std::nullopt;
      deflated = detail::deflate_chunk(deflater, chunk->tag, payload, rasters);
    }
    if (deflated.empty())
      detail::write_chunk(out, chunk->tag, payload);
    else
      detail::write_chunk(out, detail::kDeflatedTag, deflated);
  }
  return {};
}

Status decode_material(std::span<const std::uint8_t> bytes, const std::string& name, Material& out) {
  const auto fail = detail::material_error;
  const auto chunks = material_chunks();
  detail::MaterialDecoding decoding;
  std::vector<bool> seen(chunks.size(), false);
  Status walked = detail::walk_chunks(
      bytes, name,
      [&](std::span<const std::uint8_t> outer_tag, std::span<const std::uint8_t> outer_payload) -> Status {
        std::span<const std::uint8_t> tag = outer_tag;
        std::span<const std::uint8_t> payload = outer_payload;
        std::array<std::uint8_t, 4> inner_tag{};
        std::vector<std::uint8_t> inflated;
        if (printable_tag(outer_tag) == detail::kDeflatedTag) {
          std::string problem;
          if (!detail::inflate_chunk(outer_payload, inner_tag, inflated, problem))
            return fail(name, "deflated chunk " + problem);
          if (printable_tag(inner_tag) == detail::kDeflatedTag)
            return fail(name, "a deflated chunk holds another deflated chunk");
          tag = inner_tag;
          payload = inflated;
        }
        const int number = material_chunk_number(tag);
        if (number < 0) return {};  // a chunk from a newer minor version
        if (seen[number]) return fail(name, "chunk " + printable_tag(tag) + " appears twice");
        seen[number] = true;
        ByteReader r(payload);
        if (!chunks[number]->decode(r, decoding))
          return fail(name, "chunk " + printable_tag(tag) + " is truncated or has out-of-range counts");
        if (!r.at_end())
          return fail(name, "chunk " + printable_tag(tag) + " has " + std::to_string(r.remaining()) +
                                " trailing bytes");
        return {};
      });
  if (!walked.ok()) return walked;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    if (!seen[c] && chunks[c]->required)
      return fail(name, "chunk " + std::string(chunks[c]->tag) + " is missing");
  }
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    if (!seen[c] || chunks[c]->finish == nullptr) continue;
    if (std::string problem = chunks[c]->finish(decoding); !problem.empty()) return fail(name, problem);
  }
  if (Status s = validate_material(decoding.material); !s.ok()) return fail(name, s.message());
  out = std::move(decoding.material);
  return {};
}

Status list_material_chunks(std::span<const std::uint8_t> bytes, std::vector<MaterialChunkInfo>& out) {
  out.clear();
  return detail::walk_chunks(
      bytes, "material",
      [&](std::span<const std::uint8_t> tag, std::span<const std::uint8_t> payload) -> Status {
        if (printable_tag(tag) == detail::kDeflatedTag && payload.size() >= 9) {
          const std::uint32_t inflated =
              static_cast<std::uint32_t>(payload[4]) | static_cast<std::uint32_t>(payload[5]) << 8 |
              static_cast<std::uint32_t>(payload[6]) << 16 | static_cast<std::uint32_t>(payload[7]) << 24;
          out.push_back({printable_tag(payload.first(4)), payload.size() + detail::kChunkOverhead,
                         material_chunk_number(payload.first(4)) >= 0, inflated + detail::kChunkOverhead});
          return {};
        }
        out.push_back({printable_tag(tag), payload.size() + detail::kChunkOverhead,
                       material_chunk_number(tag) >= 0, 0});
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
    return detail::material_error(
        path, "is " + std::to_string(size >> 20) + " MiB, too large to be a carbtf material file");
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
