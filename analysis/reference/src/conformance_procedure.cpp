#include "carbtf/reference/conformance_procedure.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "carbtf/engine/material/material_directions.hpp"
#include "carbtf/reference/noise.hpp"
#include "carbtf/reference/subspace_synthesis.hpp"
#include "carbtf/reference/synthetic_material.hpp"

namespace carbtf::reference {
namespace {

void require(const Status& status, const std::string& what) {
  if (!status.ok()) throw std::runtime_error(what + ": " + status.message());
}

bool bitwise_equal(std::span<const float> a, std::span<const float> b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

void accumulate(StageConformance& stage, std::span<const float> tested, std::span<const float> reference,
                std::uint32_t channels) {
  stage.error = worst_of(stage.error, conformance_error(tested, reference, channels));
  stage.identical = stage.identical && bitwise_equal(tested, reference);
  ++stage.items;
}

StageConformance stage_named(std::string name) {
  StageConformance stage;
  stage.stage = std::move(name);
  return stage;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Interpolation queries: a measured pair, a point between measured directions, and grazing angles
// beyond the last measured elevation.
std::vector<std::array<double, 4>> interpolation_queries(const Material& m) {
  constexpr double d = std::numbers::pi / 180.0;
  return {{m.lights[0].theta, m.lights[0].phi, m.views.back().theta, m.views.back().phi},
          {37.0 * d, 101.0 * d, 52.0 * d, 203.0 * d},
          {89.0 * d, 10.0 * d, 87.0 * d, 190.0 * d}};
}

// The whole output as a 2 x 2 grid of blocks, each synthesized on its own (margin 0) from block
// initialization values of `whole`, against the same region of the implementation's whole images.
StageConformance blockwise_stage(const std::string& name, const Material& material,
                                 const SynthesisRequest& whole, const SynthesizedImages& images,
                                 SynthesisUnderTest& implementation) {
  StageConformance stage = stage_named("block-wise");
  std::vector<SynthesisBlock> blocks;
  const std::uint32_t half_rows = std::max(1u, whole.height / 2), half_cols = std::max(1u, whole.width / 2);
  for (std::uint32_t r = 0; r < whole.height; r += half_rows) {
    for (std::uint32_t c = 0; c < whole.width; c += half_cols) {
      SynthesisBlock block = whole;
      block.row0 = whole.row0 + static_cast<std::int32_t>(r);
      block.col0 = whole.col0 + static_cast<std::int32_t>(c);
      block.height = std::min(half_rows, whole.height - r);
      block.width = std::min(half_cols, whole.width - c);
      block.margin = 0;
      // A periodic whole's blocks are plain: beyond the fold the whole is the plain synthesis of its
      // larger region, so they are compared there.
      block.periodic_overlap = 0;
      blocks.push_back(block);
    }
  }
  const auto initial = block_initial_values(material, {}, whole, blocks);
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    SynthesisRequest request;
    static_cast<SynthesisBlock&>(request) = blocks[b];
    request.scheme = whole.scheme;
    request.poison = true;
    request.initial_values = initial[b];
    SynthesizedImages tile;
    require(implementation.synthesize(material, request, tile, nullptr),
            name + ": block-wise synthesis failed");
    for (std::size_t s = 0; s < material.subspaces.size(); ++s) {
      const std::uint32_t channels = material.subspaces[s].channels;
      // Each block row's texels beyond the fold, from both sides.
      std::vector<float> tested, expected;
      const auto row0 = static_cast<std::uint32_t>(request.row0 - whole.row0);
      const auto col0 = static_cast<std::uint32_t>(request.col0 - whole.col0);
      const std::uint32_t first =
          std::min(request.width, whole.periodic_overlap - std::min(whole.periodic_overlap, col0));
      auto append = [channels](std::vector<float>& to, const std::vector<float>& from, std::size_t texel,
                               std::size_t count) {
        const auto begin = from.begin() + static_cast<std::ptrdiff_t>(texel * channels);
        to.insert(to.end(), begin, begin + static_cast<std::ptrdiff_t>(count * channels));
      };
      for (std::uint32_t r = 0; r < request.height; ++r) {
        if (row0 + r < whole.periodic_overlap) continue;
        append(expected, images.images[s], std::size_t{row0 + r} * whole.width + col0 + first,
               request.width - first);
        append(tested, tile.images[s], std::size_t{r} * request.width + first, request.width - first);
      }
      accumulate(stage, tested, expected, channels);
    }
  }
  return stage;
}

}  // namespace

std::uint32_t CaseConformance::failures(double tolerance) const {
  return static_cast<std::uint32_t>(std::count_if(
      stages.begin(), stages.end(), [&](const StageConformance& s) { return !s.error.within(tolerance); }));
}

Material near_unit_root_material() {
  Material m = synthetic_material(1, 1);
  for (CarBandModel& band : m.subspaces[0].bands) {
    band.neighbourhood = {{0, -1}, {-1, 0}, {-1, -1}};
    band.gamma = {0.99f, 0.99f, -0.9801f};
    band.sigma = 1.0f;
    band.band_std = 1.0f / (1.0f - 0.99f * 0.99f);  // the stationary std of the separable field
  }
  return m;
}

std::vector<ConformanceCase> extreme_conformance_cases(std::uint32_t large_size) {
  std::vector<ConformanceCase> cases;
  cases.push_back(
      {"near-unit-root bands (spectral radius 0.99) at 1024x1024", near_unit_root_material(), 1024});

  // 12 neighbours (the analysis's widest) and 16 (the GPU's limit).
  Material widest = synthetic_material(2, 3, 3, 12);
  CarBandModel& sixteen = widest.subspaces[1].bands[0];
  for (std::int8_t dc = -2; dc <= 1; ++dc) sixteen.neighbourhood.push_back({-3, dc});
  sixteen.gamma.assign(sixteen.neighbourhood.size(), 0.8f / static_cast<float>(sixteen.neighbourhood.size()));
  cases.push_back(
      {"largest neighbourhoods (12 and 16 neighbours), 3 levels, 512x512", std::move(widest), 512});

  // Subspace means and contrasts spread over 8 decades, as specular and dark measurements are.
  Material hdr = synthetic_material(3, 3);
  const float scales[] = {1e-4f, 1.0f, 1e4f};
  for (std::size_t s = 0; s < 3; ++s) {
    for (float& v : hdr.subspaces[s].colour_mean) v *= scales[s];
    for (float& v : hdr.subspaces[s].colour_transform) v *= scales[s];
  }
  cases.push_back({"HDR: means and contrasts over 8 decades, 512x512", std::move(hdr), 512});

  cases.push_back({"periodic: 256x256 folded over 32 texels, 3 levels", synthetic_material(2, 3), 256,
                   default_periodic_overlap(256, 256)});

  const std::string large = std::to_string(large_size);
  cases.push_back({"large: " + large + "x" + large + ", 3 levels", synthetic_material(1, 3), large_size});
  return cases;
}

CaseConformance run_conformance_case(const ConformanceCase& test_case, const ConformanceSettings& settings,
                                     SynthesisUnderTest& implementation) {
  const Material& material = test_case.material;
  const std::string& name = test_case.name;
  const std::uint32_t size = test_case.size;
  CaseConformance report;
  report.name = name;
  SynthesisRequest request;
  request.seed = settings.seed;
  request.width = request.height = size;
  request.margin = settings.margin;
  request.poison = true;
  request.scheme = settings.scheme;
  request.periodic_overlap = test_case.periodic_overlap;
  const std::size_t count = material.subspaces.size();

  // CPU float32 stages: the bands, which become the collapsed levels once compared and are then freed.
  // The implementation's captures stay where it keeps them (run(), no image read back) and the CPU
  // images are computed again for the colour check, after the stages are gone; the float64 reference
  // comes last, a few subspaces at a time, after release(). One image-sized copy of each kind at a time
  // bounds a 4096^2 case's memory.
  const SynthesisBlock& block = request;
  std::vector<SubspaceStages> stages(count);
  std::vector<std::vector<float>> cpu(count);
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t s = 0; s < count; ++s) {
    cpu[s].resize(std::size_t{size} * size * material.subspaces[s].channels);
    synthesize_subspace(material, static_cast<std::uint32_t>(s), block, cpu[s], &stages[s]);
    std::vector<float>().swap(cpu[s]);
  }
  report.reference_ms = milliseconds_since(start);

  StageConformance noise = stage_named("noise"), band = stage_named("band fields"),
                   collapse = stage_named("collapse"), colour = stage_named("colour"),
                   interpolation = stage_named("interpolation");
  for (SynthesisStage capture : {SynthesisStage::noise, SynthesisStage::car, SynthesisStage::collapse}) {
    request.capture = capture;
    require(implementation.run(material, request), name + ": synthesis failed");
    for (std::uint32_t s = 0; s < count; ++s) {
      const SubspaceModel& model = material.subspaces[s];
      for (std::uint32_t level = 0; level < model.levels; ++level) {
        for (std::uint32_t c = 0; c < model.channels; ++c) {
          std::vector<float> tested;
          std::uint32_t rows = 0, cols = 0;
          require(implementation.read_band(s, level, c, tested, rows, cols), name + ": reading a band");
          const std::size_t index = std::size_t{level} * model.channels + c;
          if (capture == SynthesisStage::noise) {
            const TextureRegion& region = stages[s].regions[level];
            std::vector<float> expected(tested.size());
            fill_noise_block(request.seed, field_id_of(s, level, c), static_cast<std::int32_t>(region.row0),
                             static_cast<std::int32_t>(region.col0), cols, rows, expected, 1);
            accumulate(noise, tested, expected, 1);
          } else if (capture == SynthesisStage::car) {
            const float mean = model.bands[index].mean;
            for (float& v : tested) v = mean + v;  // the reference's band is mean + y, one float add
            accumulate(band, tested, stages[s].band[index], 1);
          } else {
            accumulate(collapse, tested, stages[s].band[index], 1);  // G since the car pass
            std::vector<float>().swap(stages[s].band[index]);
          }
        }
      }
      if (capture == SynthesisStage::car) collapse_band_stages(stages[s]);
    }
  }
  stages = {};
  request.capture = SynthesisStage::none;
  SynthesisTiming timing;
  SynthesizedImages images;
  require(implementation.synthesize(material, request, images, &timing), name + ": synthesis failed");
  report.implementation_ms = timing.total_ms;
  for (std::size_t s = 0; s < count; ++s) {
    cpu[s].resize(std::size_t{size} * size * material.subspaces[s].channels);
    synthesize_subspace(material, static_cast<std::uint32_t>(s), block, cpu[s]);
    accumulate(colour, images.images[s], cpu[s], material.subspaces[s].channels);
    std::vector<float>().swap(cpu[s]);
  }
  MaterialDirections directions;
  require(MaterialDirections::build(material, directions), name);
  for (const auto& [lt, lp, vt, vp] : interpolation_queries(material)) {
    const PairWeights weights = directions.weights(lt, lp, vt, vp);
    std::vector<float> tested;
    require(implementation.interpolate(material, weights, tested), name + ": interpolation failed");
    std::vector<float> expected(tested.size());
    // The stage alone: both sides interpolate the implementation's images (the colour stage compared them).
    interpolate_subspaces(material, weights, images.images, expected);
    accumulate(interpolation, tested, expected, material.subspaces[0].channels);
  }
  implementation.release();  // the blocks allocate their own, smaller buffers
  const StageConformance blockwise = blockwise_stage(name, material, request, images, implementation);
  const unsigned batch = std::max(1u, std::thread::hardware_concurrency());
  for (std::size_t first = 0; first < count; first += batch) {
    std::vector<std::uint32_t> list;
    for (std::size_t s = first; s < std::min<std::size_t>(count, first + batch); ++s)
      list.push_back(static_cast<std::uint32_t>(s));
    const auto f64 = synthesize_subspaces_f64(material, list, block);
    for (const std::uint32_t s : list) {
      report.float32_vs_float64 =
          worst_of(report.float32_vs_float64,
                   conformance_error(images.images[s], f64[s], material.subspaces[s].channels));
    }
  }
  report.stages = {noise, band, collapse, colour, interpolation, blockwise};
  return report;
}

std::vector<GrowthRow> float32_growth(const std::vector<std::uint32_t>& sizes,
                                      const ConformanceSettings& settings, SynthesisUnderTest& implementation,
                                      const std::function<void(const GrowthRow&)>& progress) {
  const Material stiff = near_unit_root_material();
  std::vector<GrowthRow> rows;
  for (const std::uint32_t size : sizes) {
    SynthesisRequest request;
    request.seed = settings.seed;
    request.width = request.height = size;
    request.margin = settings.margin;
    request.scheme = settings.scheme;
    // One whole-size copy of each kind at a time: the implementation's buffers go once its image is
    // read back, and its image once compared, before the float64 image (twice the size) is made.
    SynthesizedImages tested;
    require(implementation.synthesize(stiff, request, tested, nullptr),
            "float32 growth at " + std::to_string(size) + ": synthesis failed");
    implementation.release();
    const SynthesisBlock& block = request;
    std::vector<float> f32(std::size_t{size} * size * 3);
    synthesize_subspace(stiff, 0, block, f32);
    GrowthRow row;
    row.size = size;
    row.implementation_bits = bitwise_equal(tested.images[0], f32);
    tested = {};
    std::vector<double> f64(f32.size());
    synthesize_subspace(stiff, 0, block, f64);
    row.float32_vs_float64 = conformance_error(f32, f64, 3);
    rows.push_back(row);
    if (progress) progress(row);
  }
  return rows;
}

}  // namespace carbtf::reference
