#include "report/material_summary.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "carbtf/engine/material/material_file.hpp"
#include "carbtf/engine/material/range_tiles.hpp"
#include "cli/cli_support.hpp"

namespace carbtf::cli {

namespace {

// The value as printable text: a hostile settings chunk must not send control bytes to the terminal.
std::string setting(const Material& m, const std::string& key) {
  for (const auto& [k, v] : m.settings) {
    if (k != key) continue;
    std::string text = v;
    for (char& c : text) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte < 0x20 || byte == 0x7f) c = '?';
    }
    return text;
  }
  return "?";
}

}  // namespace

void print_material_summary(const std::string& path) {
  Material material;
  std::vector<std::uint8_t> bytes;
  check(read_material_file_bytes(path, bytes), "cannot read the material");
  check(decode_material(bytes, path, material), "cannot read the material");
  std::vector<MaterialChunkInfo> chunks;
  check(list_material_chunks(bytes, chunks), "cannot list the material's chunks");

  std::size_t bands = 0, repaired = 0, constant = 0, white = 0, neighbours = 0;
  std::uint32_t levels = 0, fewest_levels = material.subspaces.empty() ? 0 : material.subspaces[0].levels;
  for (const SubspaceModel& s : material.subspaces) {
    levels = std::max(levels, s.levels);
    fewest_levels = std::min(fewest_levels, s.levels);
    for (const CarBandModel& b : s.bands) {
      ++bands;
      neighbours += b.neighbourhood.size();
      repaired += (b.flags & car_band_repaired) != 0;
      constant += (b.flags & car_band_constant) != 0;
      white += (b.flags & car_band_white_noise) != 0;
    }
  }
  // The version the file says it was written in (the header after the signature; decoding checked it).
  const unsigned minor = unsigned{bytes[6]} | unsigned{bytes[7]} << 8;
  std::printf("material:     %s (format %u.%u)\n", path.c_str(), unsigned{kMaterialFormatMajor}, minor);
  std::printf("source:       %s\n", setting(material, "source").c_str());
  std::printf("image size:   %s\n", setting(material, "image_size").c_str());
  std::printf("directions:   %zu lights x %zu views\n", material.lights.size(), material.views.size());
  const std::string level_range = fewest_levels == levels
                                      ? std::to_string(levels)
                                      : std::to_string(fewest_levels) + " to " + std::to_string(levels);
  std::printf(
      "subspaces:    %zu, %s pyramid levels, %zu CAR bands (%.1f neighbours on average; %zu repaired, %zu "
      "constant, "
      "%zu white noise)\n",
      material.subspaces.size(), level_range.c_str(), bands,
      bands ? static_cast<double>(neighbours) / static_cast<double>(bands) : 0.0, repaired, constant, white);
  if (material.range.tile_size > 0) {
    const JoinSteps joins = measure_join_steps(material.range);
    std::printf(
        "range tiles:  %u tiles of %u x %u texels from %u patches; cuts %s, height step across them %.2fx "
        "the "
        "relief's (%.3f against %.3f texels)\n",
        range_tile_count(material.range), material.range.tile_size, material.range.tile_size,
        2 * material.range.edge_colours,
        material.range.feather
            ? ("feathered over " + std::to_string(2 * material.range.feather + 1) + " texels").c_str()
            : "hard",
        joins.elsewhere > 0 ? joins.across / joins.elsewhere : 0.0, joins.across, joins.elsewhere);
  } else {
    std::printf("range tiles:  none\n");
  }
  if (!material.range.tone.empty()) {
    std::size_t whole = 0, none = 0;
    for (const SubspaceModel& s : material.subspaces) {
      whole += s.tone_weight == 1.0f ? 1 : 0;
      none += s.tone_weight == 0.0f ? 1 : 0;
    }
    std::printf("relief tone:  taken whole by %zu subspaces, by none %zu, in part by %zu\n", whole, none,
                material.subspaces.size() - whole - none);
    const auto& chroma = material.range.tone_chroma;
    if (tone_planes(material.range) == 3) {
      std::printf("tone colour:  per texel (R, G and B planes)\n");
    } else if (chroma != std::array<float, 3>{1.0f, 1.0f, 1.0f}) {
      std::printf("tone colour:  red, green and blue follow it by %.2f, %.2f and %.2f\n", chroma[0],
                  chroma[1], chroma[2]);
    } else {
      std::printf("tone colour:  grey\n");
    }
  }
  if (material.range.tile_size > 0) {
    if (material.range.shadow_scale > 0.0f) {
      std::printf("shadows:      cast by the relief, heights x %.2f\n", material.range.shadow_scale);
    } else {
      std::printf("shadows:      none\n");
    }
    if (material.range.specular_strength > 0.0f) {
      std::printf("highlights:   a specular lobe on the relief, strength %.4g, gloss %.0f",
                  material.range.specular_strength, material.range.specular_gloss);
      if (material.range.specular_view_power > 0.0f) {
        std::printf(", growing with the view's tilt as (1 / cos theta)^%.2g",
                    material.range.specular_view_power);
      }
      std::printf("\n");
    } else {
      std::printf("highlights:   none\n");
    }
    if (material.range.chroma_levels == 0) {
      std::printf("relief chroma: at the relief's own level (the measurement's colour at full resolution)\n");
    } else {
      std::printf(
          "relief chroma: %u mip level(s) above its brightness (the measurement's colour resolution)\n",
          material.range.chroma_levels);
    }
  }
  if (material.pair_gains.empty()) {
    std::printf("pair gains:   none (each pair has its subspace image's mean colour)\n");
  } else {
    std::vector<std::uint8_t> codes = material.pair_gains;
    std::sort(codes.begin(), codes.end());
    const auto gain = [](std::uint8_t code) { return static_cast<double>(pair_gain_of_code(code)); };
    std::printf(
        "pair gains:   per light, view and colour channel, %.2fx to %.2fx (half of them within %.2fx to "
        "%.2fx)\n",
        gain(codes.front()), gain(codes.back()), gain(codes[codes.size() / 4]),
        gain(codes[codes.size() * 3 / 4]));
  }
  std::printf("file size:    %zu bytes (%.1f KiB)\n", bytes.size(),
              static_cast<double>(bytes.size()) / 1024.0);
  std::printf("  %-6s %10s %7s\n", "chunk", "bytes", "share");
  std::printf("  %-6s %10d %6.1f%%\n", "header", 12, 1200.0 / static_cast<double>(bytes.size()));
  for (const MaterialChunkInfo& c : chunks) {
    const std::string deflated =
        c.inflated_bytes > 0 ? " (deflated from " + std::to_string(c.inflated_bytes) + ")" : std::string();
    std::printf("  %-6s %10llu %6.1f%%%s%s\n", c.tag.c_str(), static_cast<unsigned long long>(c.total_bytes),
                100.0 * static_cast<double>(c.total_bytes) / static_cast<double>(bytes.size()),
                deflated.c_str(), c.known ? "" : " (unknown, skipped)");
  }
  unsigned width = 0, height = 0;
  if (std::sscanf(setting(material, "image_size").c_str(), "%ux%u", &width, &height) == 2) {
    const double raw =
        static_cast<double>(material.lights.size() * material.views.size()) * width * height * 3.0;
    std::printf("raw 8-bit:    %.1f MiB; compression ratio 1 : %.0f\n", raw / 1048576.0,
                raw / static_cast<double>(bytes.size()));
  }
}

}  // namespace carbtf::cli
