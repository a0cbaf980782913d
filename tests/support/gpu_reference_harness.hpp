// The GPU synthesis against its CPU float32 twin (docs/design.md 4.4), the one way the tests compare them:
// a material and a request run across a matrix of CAR schemes, work-batch caps, loop caps and periodic
// overlaps, every listed subspace image required equal to the reference bit for bit (both sides follow
// one operation order with no contraction, so the expected agreement is exact).
#pragma once

#include <catch2/catch.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "test_support.hpp"

namespace carbtf::test {

inline std::unique_ptr<SubspaceSynthesizer> make_synthesizer(Context& context) {
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  const Status status = SubspaceSynthesizer::create(context, synthesizer);
  INFO(status.message());
  REQUIRE(status.ok());
  return synthesizer;
}

inline SynthesizedImages gpu_synthesize(SubspaceSynthesizer& synthesizer, const Material& m,
                                        const SynthesisRequest& request) {
  SynthesizedImages images;
  const Status status = synthesizer.synthesize(m, request, images);
  INFO(status.message());
  REQUIRE(status.ok());
  return images;
}

// The CPU float32 reference of subspace image `s` of `block`.
inline std::vector<float> reference_subspace(const Material& m, std::uint32_t s,
                                             const SynthesisBlock& block) {
  std::vector<float> out(std::size_t{block.width} * block.height * m.subspaces[s].channels);
  reference::synthesize_subspace(m, s, block, out);
  return out;
}

struct SynthesisMatrix {
  std::vector<CarScheme> schemes{CarScheme::serial, CarScheme::wavefront};  // or automatic
  std::vector<VkDeviceSize> batch_caps{0};  // SubspaceSynthesizer::set_max_batch_bytes (0: the device's)
  std::vector<std::uint32_t> loop_caps{0};  // set_max_loop_iterations (0: the lavapipe-safe default)
  std::vector<std::uint32_t> overlaps;      // periodic overlaps; empty: the request's own
};

// What one run of the matrix found, for the checks a test adds (batch counts, say).
struct MatrixRun {
  CarScheme scheme = CarScheme::serial;
  VkDeviceSize batch_cap = 0;
  std::uint32_t loop_cap = 0;
  std::uint32_t overlap = 0;
  std::uint32_t batches = 0;
  SynthesizedImages images;
};

// Synthesizes `request` for every combination of `matrix` and requires each subspace image it lists (all
// when its list is empty) bit for bit equal to the reference, computed once per overlap. The synthesizer's
// caps are restored to the defaults afterwards.
inline std::vector<MatrixRun> require_gpu_matches_reference(SubspaceSynthesizer& synthesizer,
                                                            const Material& m, SynthesisRequest request,
                                                            const SynthesisMatrix& matrix = {}) {
  std::vector<std::uint32_t> subspaces = request.subspaces;
  if (subspaces.empty()) {
    for (std::uint32_t s = 0; s < m.subspaces.size(); ++s) subspaces.push_back(s);
  }
  const std::vector<std::uint32_t> overlaps =
      matrix.overlaps.empty() ? std::vector<std::uint32_t>{request.periodic_overlap} : matrix.overlaps;
  std::vector<MatrixRun> runs;
  for (const std::uint32_t overlap : overlaps) {
    request.periodic_overlap = overlap;
    std::map<std::uint32_t, std::vector<float>> expected;
    for (const std::uint32_t s : subspaces) expected[s] = reference_subspace(m, s, request);
    for (const CarScheme scheme : matrix.schemes) {
      for (const VkDeviceSize batch_cap : matrix.batch_caps) {
        for (const std::uint32_t loop_cap : matrix.loop_caps) {
          INFO(car_scheme_name(scheme) << ", batch cap " << batch_cap << " bytes, loop cap " << loop_cap
                                       << ", periodic overlap " << overlap);
          request.scheme = scheme;
          synthesizer.set_max_batch_bytes(batch_cap);
          synthesizer.set_max_loop_iterations(loop_cap);
          MatrixRun run{scheme, batch_cap, loop_cap, overlap, 0, gpu_synthesize(synthesizer, m, request)};
          run.batches = synthesizer.batch_count();
          if (scheme != CarScheme::automatic) REQUIRE(synthesizer.scheme() == scheme);
          for (const std::uint32_t s : subspaces) {
            INFO("subspace " << s);
            require_bitwise_equal(run.images.images[s], expected[s], std::size_t{request.width} * 3);
          }
          runs.push_back(std::move(run));
        }
      }
    }
  }
  synthesizer.set_max_batch_bytes(0);
  synthesizer.set_max_loop_iterations(0);
  return runs;
}

}  // namespace carbtf::test
