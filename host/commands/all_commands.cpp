#include "commands/commands.hpp"

#include "cli/cli_support.hpp"

namespace carbtf::cli {

void register_all_commands(CLI::App& app) {
  register_devices_command(app);
  register_noise_command(app);
  register_demo_command(app);
  register_sample_command(app);
  register_info_command(app);
  register_analyze_command(app);
  register_normals_command(app);
  register_synth_command(app);
  register_conform_command(app);
  register_render_command(app);
  register_fidelity_command(app);
  register_bench_command(app);
  check_every_option(app);
}

}  // namespace carbtf::cli
