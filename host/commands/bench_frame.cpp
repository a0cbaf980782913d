// `carbtf bench frame`: N frames of a material on a mesh with the camera and the light orbiting it.
// Each frame works out what it needs (scene pruning), synthesizes only the subspace images no earlier
// frame needed and copies them into their layers (ResidentImages), then renders. It reports, per frame
// and as median and p95, the GPU timestamps of synthesis with its copy and of the render pass, and the
// frame's CPU wall time (pruning, recording, submit, wait), as a table and a CSV.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "bench/frame_bench.hpp"
#include "bench/frame_parts.hpp"
#include "bench/frame_pass.hpp"
#include "carbtf/engine/synthesis/subspace_synthesizer.hpp"
#include "carbtf/engine/vulkan/gpu_timer.hpp"
#include "cli/cli_support.hpp"
#include "commands/commands.hpp"
#include "scene/material_render.hpp"
#include "scene/orbit.hpp"
#include "scene/scene_mesh.hpp"

namespace carbtf::cli {
namespace {

namespace fs = std::filesystem;

struct FrameBenchOptions {
  DeviceOptions device;
  std::string material;  // empty: the leather sample, analysed into the output folder
  std::string mesh = "sphere";
  std::uint32_t frames = 30;
  std::uint32_t lights = 1;
  std::uint32_t width = 1920;
  std::uint32_t height = 1080;
  std::uint32_t texture_size = 0;                      // 0: what the first frame needs, up to 1024
  std::uint32_t mip_levels = 0;                        // MaterialBindingInfo::max_mip_levels
  bool hand_filtering = false;                         // !MaterialBindingInfo::hardware_filtering
  PairCoupling pair_coupling = PairCoupling::product;  // MaterialBindingInfo::pair_coupling
  bool parts = false;  // also time the render pass without each part (cost probes)
  std::string out = "bench_frame";
};

// The binding every frame draws through (seed 1, as the synthesis), with cost probe bits for --parts.
MaterialBindingInfo bench_binding_info(const FrameBenchOptions& options, std::uint32_t cost_probe_bits) {
  MaterialBindingInfo info{1};
  info.max_mip_levels = options.mip_levels;
  info.hardware_filtering = !options.hand_filtering;
  info.pair_coupling = options.pair_coupling;
  info.cost_probe = cost_probe_bits;
  return info;
}

void run_bench_frame(const FrameBenchOptions& options) {
  OwnedFolder folder(options.out);
  folder.keep();  // the results stay; only the scratch BTF is released
  const fs::path out = folder.root();
  const Material material = material_or_leather_sample(options.material, folder);
  const Mesh mesh = load_mesh(options.mesh);
  auto context = make_context(options.device);
  if (context->device_info().timestamp_valid_bits == 0) {
    throw CommandError(context->device_info().name +
                       " has no GPU timestamps on its queue; bench frame needs them");
  }
  std::unique_ptr<SubspaceSynthesizer> synthesizer;
  check(SubspaceSynthesizer::create(*context, synthesizer), "cannot build the synthesis pipelines");
  GpuTimer timer;
  check(GpuTimer::create(*context, 3, timer), "cannot create the GPU timer");

  std::uint32_t texture_size = options.texture_size;
  FramePass pass;
  RenderTargetInfo target;
  target.width = options.width;
  target.height = options.height;
  std::vector<FrameRecord> records;
  std::printf("bench frame: %u frames of %ux%u, %s, %zu subspace images in the material, on %s\n",
              options.frames, options.width, options.height, options.mesh.c_str(), material.subspaces.size(),
              context->device_info().name.c_str());
  std::fflush(stdout);
  // Only what the frame can use: the subspace images its (light, view) pairs fall in.
  const std::unique_ptr<ScenePruner> pruner = make_scene_pruner(material);
  for (std::uint32_t i = 0; i < options.frames; ++i) {
    const RenderScene scene = orbiting_scene(i, options.frames, options.lights);
    const auto start = std::chrono::steady_clock::now();
    SceneNeeds needs;
    check(pruner->needs(mesh, scene, options.width, options.height, needs), "cannot prune the scene");
    if (!pass.resident) {
      // The first frame fixes the texture size and the pass; later frames only add images.
      if (texture_size == 0) texture_size = needs.texture_size;
      const std::uint32_t overlap = needs.periodic ? default_periodic_overlap(texture_size, texture_size) : 0;
      pass = make_frame_pass(*context, material, mesh, target, texture_size, overlap,
                             bench_binding_info(options, 0));
    }
    FrameRecord record;
    record.frame = i;
    // Only the images no earlier frame needed: synthesized on their own, copied into their layers.
    const std::vector<std::uint32_t> added = pass.resident->missing(needs.subspaces);
    record.synthesized = added.size();
    if (!added.empty()) {
      SynthesisRequest request;
      request.seed = 1;
      request.width = request.height = texture_size;
      request.periodic_overlap = pass.resident->textures().periodic_overlap;
      request.subspaces = added;
      check(synthesizer->prepare(material, request), "cannot plan the synthesis");
    }
    check(context->submit_and_wait([&](VkCommandBuffer cb) {
      timer.record_reset(cb);
      timer.record_timestamp(cb, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
      if (!added.empty()) {
        if (Status s = synthesizer->record(cb); !s.ok()) return s;
        if (Status s = pass.resident->record_add(cb, *synthesizer, added); !s.ok()) return s;
        if (Status s = pass.binding->set_layers(material, pass.resident->layers()); !s.ok()) return s;
      }
      timer.record_timestamp(cb, 1);
      if (Status s = pass.renderer->record(cb, scene); !s.ok()) return s;
      timer.record_timestamp(cb, 2);
      return Status{};
    }),
          "frame " + std::to_string(i) + " failed");
    record.resident = pass.resident->resident_count();
    record.wall_ms = seconds_since(start) * 1e3;
    check(timer.elapsed_ms(0, 1, record.synthesis_gpu_ms), "cannot read the GPU timestamps");
    check(timer.elapsed_ms(1, 2, record.render_gpu_ms), "cannot read the GPU timestamps");
    if (added.empty()) record.synthesis_gpu_ms = 0.0;
    records.push_back(record);
  }
  if (options.parts) {
    FramePartsSetup setup{*context, timer, material, pass.resident->textures(), target, mesh};
    run_frame_parts(setup, bench_binding_info(options, 0), options.frames, options.lights, out);
  }
  check_validation(*context);

  char line[256];
  std::snprintf(
      line, sizeof line,
      "bench frame: %u frames of %ux%u, %s, %u light%s, on %s, texture %u^2 with %u mip levels, filtered "
      "%s, %s direction taps, %zu of %zu subspace images resident at the end\n\n",
      options.frames, options.width, options.height, options.mesh.c_str(), options.lights,
      options.lights == 1 ? "" : "s", context->device_info().name.c_str(), texture_size,
      pass.binding->mip_levels(), pass.binding->hardware_filtering() ? "by the sampler" : "by hand",
      direction_taps_name(pass.binding->pair_coupling()), pass.resident->resident_count(),
      material.subspaces.size());
  std::printf("%s%s", line, write_frame_bench_report(out, records, line).c_str());
  std::printf("wrote %s/bench_frame.csv and bench_frame.md\n", out.string().c_str());
}

}  // namespace

void register_bench_frame_command(CLI::App& bench) {
  auto options = std::make_shared<FrameBenchOptions>();
  auto* command =
      bench.add_subcommand("frame",
                           "Frames of a material on a mesh, camera and light orbiting: GPU time of synthesis "
                           "and of the render pass, CPU wall time per frame, median and p95, table and CSV");
  command->add_option("--material", options->material,
                      "Material file (default: the leather sample, analysed at 64^2 into the output folder)");
  command
      ->add_option("--mesh", options->mesh,
                   "plane, sphere, cylinder, torus, or an OBJ file with texture coordinates")
      ->capture_default_str();
  command->add_option("--frames", options->frames, "Frames to render")
      ->check(CLI::Range(1u, 100000u))
      ->capture_default_str();
  command
      ->add_option(
          "--lights", options->lights,
          "Directional lights at 40 degrees from the pole, spread evenly in azimuth, each 1/N strong")
      ->check(CLI::Range(1u, static_cast<unsigned>(kMaxRenderLights)))
      ->capture_default_str();
  command->add_option("--width", options->width, "Frame width")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command->add_option("--height", options->height, "Frame height")
      ->check(CLI::Range(1u, 16384u))
      ->capture_default_str();
  command
      ->add_option("--texture-size", options->texture_size,
                   "Synthesized texels per side (default: what the first frame needs, up to 1024)")
      ->check(CLI::Range(16u, 8192u));
  command
      ->add_option("--mip-levels", options->mip_levels,
                   "At most this many mip levels (0: all; 1: level 0 only)")
      ->check(CLI::Range(0u, 16u))
      ->capture_default_str();
  command->add_flag(
      "--parts", options->parts,
      "Also render the frames with each part of the fragment stage (direction lookups, pair table, "
      "subspace image reads, relief, parallax ray march) replaced by a constant, with offset mapping (one "
      "height read) in the march's place, and with the other --direction-taps, in turn with the full pass, "
      "and report what each part costs (timing only; "
      "writes bench_frame_parts.md and .csv)");
  command->add_flag("--hand-filtering", options->hand_filtering,
                    "Filter the subspace images by hand, as the CPU reference does, instead of through the "
                    "sampler's trilinear filtering (the default where the device filters RGBA32F)");
  add_direction_taps_option(*command, options->pair_coupling);
  command->add_option("--out", options->out, "Output folder")->capture_default_str();
  add_device_options(*command, options->device);
  command->callback([options] { run_bench_frame(*options); });
}

}  // namespace carbtf::cli
