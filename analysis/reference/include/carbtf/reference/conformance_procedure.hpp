// The conformance procedure (`carbtf conform`, and any host engine's own conformance run): a synthesis
// implementation under test against the CPU reference, stage by stage.
//
// For each case (a material at a size):
//   noise, band fields, collapse: the implementation's captured bands against the reference's stages;
//   colour: its subspace images against the reference's;
//   interpolation: its blend of its own images against the reference blend of the same images, at a
//     measured pair, a pair between measured directions and a pair beyond the last elevation;
//   block-wise: a 2 x 2 grid of blocks, each synthesized alone (margin 0) from block initialization
//     values, against the same regions of the whole;
//   float32 against the float64 reference (reported, not judged).
// Errors are max and RMS absolute differences relative to the reference's std (conformance.hpp). Both
// sides follow one operation order, so a conforming implementation is exact: the tolerance is for
// reporting how far a failing one is off.
//
// The built-in extreme cases are the stiff and extreme materials: near-unit-root bands, the largest
// neighbourhoods, HDR means and contrasts over 8 decades, and a large image. The float32 growth study
// reports float32 against float64 with field size on the near-unit-root band.
//
// The implementation is reached through SynthesisUnderTest, so this library needs no Vulkan: the
// GPU's SubspaceSynthesizer is adapted by SynthesisAdapter where a caller has it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "carbtf/engine/material/direction_interpolation.hpp"
#include "carbtf/engine/material/material.hpp"
#include "carbtf/engine/status.hpp"
#include "carbtf/engine/synthesis/synthesis_request.hpp"
#include "carbtf/reference/conformance.hpp"

namespace carbtf::reference {

// What the procedure asks of the implementation under test; SubspaceSynthesizer's methods of the same
// names define the meaning.
class SynthesisUnderTest {
 public:
  virtual ~SynthesisUnderTest() = default;
  // Synthesizes and keeps the result where read_band() and interpolate() can reach it.
  virtual Status run(const Material& material, const SynthesisRequest& request) = 0;
  virtual Status read_band(std::uint32_t subspace, std::uint32_t level, std::uint32_t channel,
                           std::vector<float>& out, std::uint32_t& rows, std::uint32_t& cols) = 0;
  virtual Status synthesize(const Material& material, const SynthesisRequest& request, SynthesizedImages& out,
                            SynthesisTiming* timing) = 0;
  virtual Status interpolate(const Material& material, const PairWeights& weights,
                             std::vector<float>& out) = 0;
  // Frees what the last synthesis holds (the procedure's memory bound relies on it).
  virtual void release() = 0;
};

// Adapts any synthesizer with SubspaceSynthesizer's methods; the caller that has one instantiates it.
template <class Synthesizer>
class SynthesisAdapter final : public SynthesisUnderTest {
 public:
  explicit SynthesisAdapter(Synthesizer& synthesizer) : synthesizer_(synthesizer) {}
  Status run(const Material& material, const SynthesisRequest& request) override {
    return synthesizer_.run(material, request);
  }
  Status read_band(std::uint32_t subspace, std::uint32_t level, std::uint32_t channel,
                   std::vector<float>& out, std::uint32_t& rows, std::uint32_t& cols) override {
    return synthesizer_.read_band(subspace, level, channel, out, rows, cols);
  }
  Status synthesize(const Material& material, const SynthesisRequest& request, SynthesizedImages& out,
                    SynthesisTiming* timing) override {
    return synthesizer_.synthesize(material, request, out, timing);
  }
  Status interpolate(const Material& material, const PairWeights& weights, std::vector<float>& out) override {
    return synthesizer_.interpolate(material, weights, out);
  }
  void release() override { synthesizer_.release(); }

 private:
  Synthesizer& synthesizer_;
};

struct ConformanceSettings {
  std::uint64_t seed = 1;
  std::uint32_t margin = 64;  // burn-in per level
  CarScheme scheme = CarScheme::automatic;
};

struct StageConformance {
  std::string stage;
  std::uint32_t items = 0;  // images or bands compared
  ConformanceError error;
  bool identical = true;  // every item equal bit for bit
};

struct CaseConformance {
  std::string name;
  std::vector<StageConformance> stages;  // noise, band fields, collapse, colour, interpolation, block-wise
  double implementation_ms = 0.0;        // its own timing of the whole synthesis (0 if it has none)
  double reference_ms = 0.0;             // the CPU float32 reference, one thread
  ConformanceError float32_vs_float64;   // the implementation's images against the float64 reference
  // The stages beyond `tolerance` (max error relative to the std).
  std::uint32_t failures(double tolerance) const;
};

struct ConformanceCase {
  std::string name;
  Material material;
  std::uint32_t size = 0;
  std::uint32_t periodic_overlap = 0;  // SynthesisBlock::periodic_overlap
};

// The stiff and extreme cases; the large one at `large_size`^2.
std::vector<ConformanceCase> extreme_conformance_cases(std::uint32_t large_size);

// A near-unit-root band: separable (1 - 0.99 z1)(1 - 0.99 z2), spectral radius 0.99, the largest the
// analysis keeps after repair; band_std is its stationary std.
Material near_unit_root_material();

// One case, every stage. Throws std::runtime_error naming the case when the implementation reports an
// error (a failed synthesis is not a conformance figure).
CaseConformance run_conformance_case(const ConformanceCase& test_case, const ConformanceSettings& settings,
                                     SynthesisUnderTest& implementation);

struct GrowthRow {
  std::uint32_t size = 0;
  ConformanceError float32_vs_float64;  // the CPU float32 reference against float64
  bool implementation_bits = false;     // the implementation equals the CPU float32 reference bit for bit
};

// float32 error growth with field size on the near-unit-root band, against float64; `progress` (may
// be empty) is called after each size.
std::vector<GrowthRow> float32_growth(const std::vector<std::uint32_t>& sizes,
                                      const ConformanceSettings& settings, SynthesisUnderTest& implementation,
                                      const std::function<void(const GrowthRow&)>& progress = {});

}  // namespace carbtf::reference
