// The block a subspace-image synthesis computes and the block initialization values that make a block
// equal to the same region of a larger synthesis: the plain data a host passes in a SynthesisRequest,
// shared by the GPU synthesizer and the CPU reference (docs/design.md 4.4). How each level and band
// region follows from a block is internal to carbtf and not installed
// (engine/internal/carbtf/engine/internal/synthesis_layout.hpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/material/texture_window.hpp"

namespace carbtf {

// A rectangle of an unbounded field, in absolute coordinates.
struct TextureRegion {
  std::int64_t row0 = 0;
  std::int64_t col0 = 0;
  std::int64_t rows = 0;
  std::int64_t cols = 0;
  bool operator==(const TextureRegion&) const = default;
};

// What a synthesis computes, on the CPU and the GPU alike: the window of the unbounded texture of `seed`
// (texture_window.hpp), rows [row0, row0 + height) and columns [col0, col0 + width), each band's CAR
// recursion started from zeros some rows above and columns each side of its level region (burn-in): as
// many as the band's stability needs for its zero start to fade below a thousandth of a standard
// deviation, at most `margin` (docs/design.md 4.4). The window with its burn-in must lie within the
// random fields' 32-bit coordinates; a synthesis refuses one that does not.
//
// With periodic_overlap p > 0 the output is periodic instead (docs/design.md 4.4): the synthesis covers
// (width + p) x (height + p) texels from (row0, col0), and the colour step folds the last p columns and
// rows onto the first p with variance-keeping weights, so that the width x height output tiles without
// a seam (closed meshes: sphere, cylinder, torus). Texels at least p from the top and left edges equal
// the non-periodic synthesis of the larger block.
struct SynthesisBlock : TextureWindow {
  std::uint32_t margin = 64;  // the most burn-in any band gets
  SynthesisBlock() : TextureWindow{.width = 512, .height = 512} {}
};

// The overlap a periodic synthesis of a width x height image uses by default: an eighth of the shorter
// side, from 4 to 64 texels (wider than the measured materials' structures at 256^2, a small share of
// the work at 1024^2).
std::uint32_t default_periodic_overlap(std::uint32_t width, std::uint32_t height);

// The level-0 region a block's synthesis computes: the block, grown by its periodic overlap.
TextureRegion synthesized_region(const SynthesisBlock& block);

// Whether the block, grown by its periodic overlap and by `margin` above and on both sides (the most
// burn-in a band takes), lies within the synthesis's 32-bit texture coordinates (texture_window.hpp). The
// GPU synthesis and the CPU reference refuse a block that does not.
bool within_texture_coordinates(const SynthesisBlock& block);

// Block initialization values (the paper's "block initialization values"): to synthesize a block on its
// own yet equal to the same region of a larger synthesis, each band's recursion starts from that
// larger synthesis's values around the band's CAR region instead of from zeros. One field's frame holds,
// in order, the `pad` rows above its CAR region, each cols + 2 pad wide (from column col0 - pad), then
// for every region row its `pad` values to the left and its `pad` values to the right.
std::uint64_t car_frame_floats(const TextureRegion& car, std::uint32_t pad);

// Where each field's frame lies in the block initialization values of a request: fields in request
// order (subspace as listed, then level, then channel), frames back to back.
struct BlockFrameField {
  std::uint32_t subspace = 0;
  std::uint32_t level = 0;
  std::uint32_t channel = 0;
  TextureRegion car;  // the recursion's region (absolute coordinates)
  std::uint32_t pad = 1;
  std::uint64_t offset = 0;  // first value of the frame
};
struct BlockFrameLayout {
  std::vector<BlockFrameField> fields;
  std::uint64_t floats = 0;  // total
};
// `subspaces` must exist in `material` (callers validate first).
BlockFrameLayout block_frame_layout(const Material& material, const SynthesisBlock& block,
                                    std::span<const std::uint32_t> subspaces);

// Copies one field's frame (CAR region `car`, `pad`) out of the stored recursion values `source` of a
// larger synthesis of the same field, which cover `source_region` row-major (frame included: outside
// its own recursion a field's values are its frame). Returns false, writing nothing, when the frame does
// not lie inside `source_region` or `out` is shorter than car_frame_floats().
bool extract_car_frame(const TextureRegion& car, std::uint32_t pad, std::span<const float> source,
                       const TextureRegion& source_region, std::span<float> out);

}  // namespace carbtf
