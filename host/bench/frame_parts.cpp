#include "bench/frame_parts.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/frame_bench.hpp"
#include "cli/cli_support.hpp"
#include "scene/orbit.hpp"

namespace carbtf::cli {

void run_frame_parts(const FramePartsSetup& setup, const MaterialBindingInfo& base, std::uint32_t frames,
                     std::uint32_t lights, const std::filesystem::path& out) {
  std::printf(
      "bench frame: the render pass again with each part of the fragment stage replaced by a constant, "
      "and with the other --direction-taps\n");
  std::fflush(stdout);
  // The last two variants draw the whole material otherwise: parallax by offset mapping, one height read
  // instead of the ray march (MaterialBindingInfo::parallax_steps 0), and the other --direction-taps, another
  // interpolation between the measured directions.
  const PairCoupling other_coupling =
      base.pair_coupling == PairCoupling::staircase ? PairCoupling::product : PairCoupling::staircase;
  const std::string other_taps = std::string(direction_taps_name(base.pair_coupling)) + " direction taps (" +
                                 direction_taps_name(other_coupling) + " in their place)";
  struct Variant {
    std::string part;
    std::uint32_t cost_probe = 0;
    PairCoupling coupling = PairCoupling::product;
    std::optional<std::uint32_t> parallax_steps;  // the base's where not given
  };
  const std::vector<Variant> probes = {
      {"none (the full pass)", 0u, base.pair_coupling, {}},
      {"direction lookups", cost_probe::lookups, base.pair_coupling, {}},
      {"pair table reads", cost_probe::pair_reads, base.pair_coupling, {}},
      {"subspace image reads", cost_probe::subspace_reads, base.pair_coupling, {}},
      {"relief (normal, tone, horizons)", cost_probe::relief, base.pair_coupling, {}},
      {"parallax ray march", cost_probe::parallax, base.pair_coupling, {}},
      {"offset mapping (1 height read) in the march's place", 0u, base.pair_coupling, 0u},
      {other_taps, 0u, other_coupling, {}}};
  std::vector<FramePartTimes> parts;
  std::vector<std::unique_ptr<MaterialBinding>> bindings(probes.size());
  std::vector<std::unique_ptr<MeshRenderer>> renderers(probes.size());
  for (std::size_t p = 0; p < probes.size(); ++p) {
    MaterialBindingInfo info = base;
    info.cost_probe = probes[p].cost_probe;
    info.pair_coupling = probes[p].coupling;
    info.parallax_steps = probes[p].parallax_steps.value_or(base.parallax_steps);
    check(MaterialBinding::create(setup.context, setup.material, setup.textures, info, bindings[p]),
          "cannot bind");
    check(bindings[p]->upload_and_wait(), "cannot upload the material");
    check(MeshRenderer::create(setup.context, *bindings[p], setup.target, renderers[p]),
          "cannot build the render pass");
    check(renderers[p]->set_mesh(setup.mesh), "cannot upload the mesh");
    parts.push_back({probes[p].part, {}});
  }
  // Frame by frame, every variant in turn, so that the machine's drift falls on all of them alike.
  for (std::uint32_t i = 0; i < frames; ++i) {
    const RenderScene scene = orbiting_scene(i, frames, lights);
    for (std::size_t p = 0; p < probes.size(); ++p) {
      check(setup.context.submit_and_wait([&](VkCommandBuffer cb) {
        setup.timer.record_reset(cb);
        setup.timer.record_timestamp(cb, 0, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
        if (Status s = renderers[p]->record(cb, scene); !s.ok()) return s;
        setup.timer.record_timestamp(cb, 1);
        return Status{};
      }),
            "frame " + std::to_string(i) + " without the " + parts[p].part + " failed");
      double ms = 0.0;
      check(setup.timer.elapsed_ms(0, 1, ms), "cannot read the GPU timestamps");
      parts[p].render_gpu_ms.push_back(ms);
    }
  }
  check_validation(setup.context);
  const std::string heading = "bench frame --parts: render pass GPU time, " + std::to_string(frames) +
                              " frames per variant, " + setup.context.device_info().name +
                              " (timing only: a replaced part makes the picture wrong)\n\n";
  std::printf("\n%s%s", heading.c_str(), write_frame_parts_report(out, parts, heading).c_str());
  std::printf("wrote %s/bench_frame_parts.csv and bench_frame_parts.md\n\n", out.string().c_str());
}

}  // namespace carbtf::cli
