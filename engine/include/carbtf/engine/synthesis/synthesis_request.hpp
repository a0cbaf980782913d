// What a subspace-image synthesis is asked for and what it gives back: the request (block, subspaces,
// CAR scheme, stage capture), per-stage timing and the images as the host holds them. Plain data, with
// no Vulkan type, so that the GPU synthesizer (subspace_synthesizer.hpp), the CPU reference and the
// conformance procedure (carbtf::reference) share them.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "carbtf/engine/synthesis/synthesis_block.hpp"

namespace carbtf {

// How CAR recursions run on the device. serial: one invocation per field, pixels in row order (CPU
// devices such as lavapipe, where barriers are costly); wavefront: one workgroup per field, pixels of a
// step t = a * row + col in parallel with a barrier per step (GPUs). automatic picks by device type.
enum class CarScheme { automatic, serial, wavefront };
const char* car_scheme_name(CarScheme scheme) noexcept;

// The channels a GPU synthesis supports per subspace image (its output is RGBA32F).
inline constexpr std::uint32_t kMaxGpuChannels = 4;
// Neighbours per CAR band a GPU synthesis supports (the analysis fits at most 12).
inline constexpr std::uint32_t kMaxGpuNeighbours = 16;

// The stages of a synthesis, in order; a request may capture the work buffer after one of them.
enum class SynthesisStage { none, noise, car, collapse };

// The block to synthesize (synthesis_block.hpp) and what to synthesize of it.
struct SynthesisRequest : SynthesisBlock {
  // Which subspace images, in output-layer order; empty means all of them.
  std::vector<std::uint32_t> subspaces;
  CarScheme scheme = CarScheme::automatic;
  // Fill the work buffer and the output image with NaN first, so that anything left unwritten shows
  // (tests and conformance use it).
  bool poison = false;
  // Conformance: after this stage of every batch, copy the bands to host memory for read_band().
  SynthesisStage capture = SynthesisStage::none;
  // Block-wise synthesis: block initialization values laid out by block_frame_layout(material, *this,
  // subspaces as resolved), e.g. from the CPU reference's block_initial_values(). Every band's
  // recursion then starts from them instead of zeros, so the block equals the same region of the
  // larger synthesis they came from. Empty: zeros. Read during prepare() only.
  std::span<const float> initial_values;
  // Mip levels of the output image, level 0 included, each the mean of 2 x 2 texels of the one below
  // (material/mip_levels.hpp), which record() makes after the colour pass: what a render pass samples
  // (MaterialTextures::mip_levels). 0: all the size allows; 1 (the default): level 0 alone, for
  // read-back and conformance. A device that cannot blit RGBA32F with a linear filter gets 1.
  std::uint32_t mip_levels = 1;
};

// GPU time per stage, summed over batches, in milliseconds (0 where the queue has no timestamps).
struct SynthesisTiming {
  double prepare_ms = 0.0;  // frames (and the noise of a noise capture)
  double car_ms = 0.0;
  double collapse_ms = 0.0;
  double colour_ms = 0.0;
  double total_ms = 0.0;
  std::uint32_t batches = 0;
  std::uint32_t dispatches = 0;
};

// Subspace images read back to the host: images[s] holds subspace s as width * height * channels
// floats (row-major, channels interleaved), or is empty when s was not requested.
struct SynthesizedImages {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint32_t> channels;  // per subspace
  std::vector<std::vector<float>> images;
};

}  // namespace carbtf
