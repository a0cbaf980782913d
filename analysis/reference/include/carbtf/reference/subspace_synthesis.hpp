// CPU reference of subspace-image synthesis (docs/design.md 4.4), the specification the GPU pipeline must
// follow operation for operation. For subspace s of a material, seed S, output block rows
// [row0, row0 + height) x cols [col0, col0 + width) of the unbounded texture:
//  1. Regions: level 0 covers the output block; level l + 1 covers the coarse support its expand
//     needs: fine rows [a, b) need coarse rows [floor((a - 1) / 2), floor((b + 1) / 2) + 1), the same
//     for columns.
//  2. Fields: band (level l, channel c) is the CAR field (reference/car_synthesis.hpp) of field id
//     s * 128 + l * 16 + c over its level's region, with the burn-in margin given.
//  3. Collapse, from the coarsest level down: G_l = band_l + expand(G_l+1), where expand runs along
//     rows first, then along columns; each output sample sums the taps k = -2..2 in that order,
//     acc = acc + (2 w_k) * G((i - k) / 2) over the k with i - k even, w = [1 4 6 4 1] / 16.
//  4. Colour: rgb_i = mean_i + sum_j T[i][j] * G_0,j, j in order, accumulated from mean_i.
// Float32 follows this order exactly (no contraction); float64 is the same in double, the accuracy
// reference. Results are row-major, channels interleaved.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/internal/synthesis_layout.hpp"
#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"

namespace carbtf::reference {

using SubspaceBlock = SynthesisBlock;

// The intermediate stages of one subspace synthesis, per band at index level * channels + channel, over
// that level's window (level_regions()): the band (mean + CAR field) as the float32 synthesis computes
// it. collapse_band_stages() then turns them into the collapsed levels G, in place: one image-sized copy
// of the stages at a time (conform compares 4096^2 fields). A caller may free each once it has used it.
struct SubspaceStages {
  std::vector<TextureRegion> regions;  // per level
  std::vector<std::vector<float>> band;
};

// Adds to each band the expanded collapsed level above it, coarsest first, with the synthesis's own
// operations: afterwards `stages.band[i]` holds the collapsed level G. Throws std::invalid_argument when
// the bands do not match the regions.
void collapse_band_stages(SubspaceStages& stages);

// Synthesizes subspace image `subspace` into `out` (width * height * channels). Throws
// std::invalid_argument for a subspace index out of range, an output span too small or initial values
// of the wrong size. With `stages`, also keeps every band.
// Block-wise synthesis: `initial_values` (empty: every recursion starts from zeros) are the block
// initialization values laid out by block_frame_layout(material, block, {subspace}), as
// block_initial_values() computes them.
void synthesize_subspace(const Material& material, std::uint32_t subspace, const SubspaceBlock& block,
                         std::span<float> out, SubspaceStages* stages = nullptr,
                         std::span<const float> initial_values = {});
void synthesize_subspace(const Material& material, std::uint32_t subspace, const SubspaceBlock& block,
                         std::span<double> out, std::span<const float> initial_values = {});

// Synthesizes the listed subspace images (empty: all) with one task per image on `threads` threads (0:
// all hardware threads). Result indexed by subspace id, empty where not listed. `initial_values` as
// above, laid out by block_frame_layout(material, block, list). Throws like synthesize_subspace.
std::vector<std::vector<float>> synthesize_subspaces(const Material& material,
                                                     std::span<const std::uint32_t> subspaces,
                                                     const SubspaceBlock& block, unsigned threads = 0,
                                                     std::span<const float> initial_values = {});
std::vector<std::vector<double>> synthesize_subspaces_f64(const Material& material,
                                                          std::span<const std::uint32_t> subspaces,
                                                          const SubspaceBlock& block, unsigned threads = 0,
                                                          std::span<const float> initial_values = {});

// The block initialization values that let each of `blocks` be synthesized on its own (on the CPU or
// the GPU) and still equal, bit for bit in float32, the same region of the synthesis `whole`: for every
// listed subspace (empty: all) and band, the float32 recursion values of `whole` around the block's
// band (block_frame_layout()). Runs each band of `whole` once, on `threads` threads. Throws
// std::invalid_argument when a block (with its burn-in margin and frame) does not lie inside `whole`
// or the seeds differ.
std::vector<std::vector<float>> block_initial_values(const Material& material,
                                                     std::span<const std::uint32_t> subspaces,
                                                     const SubspaceBlock& whole,
                                                     std::span<const SubspaceBlock> blocks,
                                                     unsigned threads = 0);

// The 9-weight interpolation of synthesized subspace images: out = sum_k w_k * images[subspace of
// pair k]; `images[s]` holds subspace s (pixel_count * channels values) or is empty when not needed.
// Throws std::invalid_argument when a needed subspace image is missing.
void interpolate_subspaces(const Material& material, const PairWeights& weights,
                           const std::vector<std::vector<float>>& images, std::span<float> out);

}  // namespace carbtf::reference
